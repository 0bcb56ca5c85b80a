# The Pareto front of `clothsim bench accuracy`: position error against cost, log-log, one curve
# per integrator (colour) and backend/precision (dash and point: cpu double solid circles, cpu
# float dashed triangles, gpu float dotted inverted triangles); unstable runs marked along the top.
# Set by the command (gnuplot -e): format ('png' or 'svg'), out, csv, title, unstable_y (where
# the unstable marks go) and the curves as word lists: series_methods, series_targets,
# series_colours, series_styles.
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

n = words(series_methods)
method(i) = word(series_methods, i)
target(i) = word(series_targets, i)
colour(i) = int(word(series_colours, i))
style(i) = int(word(series_styles, i))
mine(i) = strcol('method') eq method(i) && strcol('target') eq target(i)
# Column `col` of curve i's rows that stayed stable (else NaN, which gnuplot leaves out).
stable(i, col) = mine(i) && strcol('status') eq 'stable' ? column(col) : NaN
unstableCost(i) = mine(i) && strcol('status') eq 'unstable' ? column('wall_per_sim_s') : NaN

plot for [i=1:n] csv using (stable(i, 'wall_per_sim_s')):(stable(i, 'pos_rms_err_rel')) \
         with linespoints lc (colour(i)) dt style(i) pt (2 * style(i) + 5) lw 1.5 \
         title method(i).' '.target(i), \
     for [i=1:n] csv using (unstableCost(i)):(real(unstable_y)) \
         with points lc (colour(i)) pt 2 ps 2 notitle, \
     NaN with points lc 'black' pt 2 ps 2 title 'unstable (x: cost until it blew up)'
