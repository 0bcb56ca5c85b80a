# The Pareto front of `clothsim bench accuracy`: position error against cost, log-log, one curve
# per integrator and backend/precision; unstable runs marked along the top.
# Set by the command (gnuplot -e): format ('png' or 'svg'), out, csv, targets and methods
# (space-separated), unstable_y (where the unstable marks go), title.
if (format eq 'png') {
    set terminal pngcairo size 1400,800 enhanced font ',11'
} else {
    set terminal svg size 1400,800 dynamic enhanced font ',11'
}
set output out
set datafile separator ','
set datafile columnheaders
set logscale xy
set format x '10^{%L}'
set format y '10^{%L}'
set xlabel 'cost: wall time per simulated second [s/s]'
set ylabel 'position RMS error / cloth extent at the final time'
set title title noenhanced
set key outside right center vertical noenhanced font ',9' spacing 1.1
set grid
set pointsize 1.2

method(i) = word(methods, i)
target(j) = word(targets, j)
# The value of column `col` on rows of integrator i and target j that stayed stable, else NaN.
pick(i, j, col) = (strcol('method') eq method(i) && strcol('target') eq target(j) \
                   && strcol('status') eq 'stable') ? column(col) : NaN
unstableCost(i, j) = (strcol('method') eq method(i) && strcol('target') eq target(j) \
                      && strcol('status') eq 'unstable') ? column('wall_per_sim_s') : NaN

plot for [i=1:words(methods)] for [j=1:words(targets)] csv \
         using (pick(i, j, 'wall_per_sim_s')):(pick(i, j, 'pos_rms_err_rel')) \
         with linespoints lc i dt j pt (2*j + 5) lw 1.5 title method(i).' '.target(j), \
     for [i=1:words(methods)] for [j=1:words(targets)] csv \
         using (unstableCost(i, j)):(real(unstable_y)) \
         with points lc i pt 2 ps 2 notitle, \
     NaN with points lc 'black' pt 2 ps 2 title 'unstable (x: cost until it blew up)'
