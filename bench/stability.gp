# `clothsim bench stability`: the largest stable time step against stiffness, mass or damping,
# log-log; measured points per integrator and backend beside the predicted bounds (lines).
# Set by the command (gnuplot -e): format ('png' or 'svg'), out, csv, sweep (stiffness, mass or
# damping), targets and methods (space-separated), title.
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
xcol = sweep eq 'stiffness' ? 'k_structural_N_per_m' : sweep eq 'mass' ? 'mass_kg' : 'damping_Ns_per_m'
set xlabel (sweep eq 'stiffness' ? 'structural stiffness K [N/m] (shear and bend scaled with it)' : \
            sweep eq 'mass' ? 'mass per vertex m [kg]' : 'damping {/Symbol m} [N s/m]')
set ylabel 'largest stable time step [s]'
set title title noenhanced
set key outside right center vertical noenhanced font ',9' spacing 1.1
set grid
set pointsize 1.3

method(i) = word(methods, i)
target(j) = word(targets, j)
row(i, j) = strcol('sweep') eq sweep && strcol('method') eq method(i) && strcol('target') eq target(j)
# Predictions are the same on every backend: drawn from the first target's rows. An infinite
# bound (implicit Euler) is an empty cell: no line, and no key entry for it.
line(i, kind) = method(i) eq 'implicit_euler' ? '' : method(i).' predicted ('.kind.')'
predicted(i, col) = row(i, 1) ? column(col) : NaN
measured(i, j, status) = row(i, j) && strcol('status') eq status ? column('measured_dt_s') : NaN

plot for [i=1:words(methods)] csv using (predicted(i, xcol)):(predicted(i, 'predicted_tight_dt_s')) \
         with lines lc i lw 2 title line(i, 'tight, power iteration'), \
     for [i=1:words(methods)] csv using (predicted(i, xcol)):(predicted(i, 'predicted_safe_dt_s')) \
         with lines lc i dt 2 lw 1 title line(i, 'safe, Gershgorin'), \
     for [i=1:words(methods)] for [j=1:words(targets)] csv \
         using (row(i, j) ? column(xcol) : NaN):(measured(i, j, 'bounded')) \
         with points lc i pt (j == 1 ? 7 : 4) title method(i).' measured '.target(j), \
     for [i=1:words(methods)] for [j=1:words(targets)] csv \
         using (row(i, j) ? column(xcol) : NaN):(measured(i, j, 'stable_to_cap')) \
         with points lc i pt (j == 1 ? 9 : 8) ps 1.8 notitle, \
     NaN with points lc 'black' pt 9 ps 1.8 title 'stable up to the cap (no bound found)'
