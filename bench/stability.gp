# `clothsim bench stability`: the largest stable time step against stiffness, mass or damping,
# log-log; measured points per integrator and backend beside the predicted bounds (lines).
# Set by the command (gnuplot -e): format ('png' or 'svg'), out, csv, sweep (stiffness, mass or
# damping), targets and methods (space-separated), title; for the mass and damping sweeps of
# explicit Euler also lambda_safe, lambda_tight [N/m], mass [kg] and damping [N s/m] of the scene.
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
set samples 400
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
measured(i, j, status) = row(i, j) && strcol('status') eq status ? column('measured_dt_s') : NaN
x(i, j) = row(i, j) ? column(xcol) : NaN

# Predicted bounds. Over stiffness: lines through each sample's prediction, from the first
# target's rows (the same on every backend); an infinite bound (implicit Euler) is an empty cell,
# so no line and no key entry. Over mass or damping (explicit Euler, λ fixed): the curve
# min(μ/λ, 2m/μ) of docs/physics.md.
line(i, kind) = method(i) eq 'implicit_euler' ? '' : method(i).' predicted ('.kind.')'
predicted(i, col) = row(i, 1) ? column(col) : NaN
euler(mu, lambda, m) = mu / lambda < 2 * m / mu ? mu / lambda : 2 * m / mu
eulerAt(x, lambda) = sweep eq 'mass' ? euler(real(damping), lambda, x) : euler(x, lambda, real(mass))

measuredPlots = 'for [i=1:words(methods)] for [j=1:words(targets)] csv using (x(i, j)):(measured(i, j, "bounded")) with points lc i pt (j == 1 ? 7 : 4) title method(i)." measured ".target(j), for [i=1:words(methods)] for [j=1:words(targets)] csv using (x(i, j)):(measured(i, j, "stable_to_cap")) with points lc i pt (j == 1 ? 9 : 8) ps 1.8 notitle, NaN with points lc "black" pt 9 ps 1.8 title "stable up to the cap (no bound found)"'

if (sweep eq 'stiffness') {
    plot for [i=1:words(methods)] csv using (predicted(i, xcol)):(predicted(i, 'predicted_tight_dt_s')) \
             with lines lc i lw 2 title line(i, 'tight, power iteration'), \
         for [i=1:words(methods)] csv using (predicted(i, xcol)):(predicted(i, 'predicted_safe_dt_s')) \
             with lines lc i dt 2 lw 1 title line(i, 'safe, Gershgorin'), \
         @measuredPlots
} else {
    plot eulerAt(x, real(lambda_tight)) with lines lc 1 lw 2 \
             title 'explicit Euler predicted min({/Symbol m}/{/Symbol l}, 2m/{/Symbol m}), {/Symbol l} tight (power iteration)' enhanced, \
         eulerAt(x, real(lambda_safe)) with lines lc 1 dt 2 lw 1 \
             title 'explicit Euler predicted, {/Symbol l} safe (Gershgorin)' enhanced, \
         @measuredPlots
}
