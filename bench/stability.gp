# `clothsim bench stability`: the largest stable time step against stiffness, mass or damping,
# log-log; measured points per integrator (colour) and backend (cpu double filled circles, gpu
# float open squares) beside the predicted bounds (lines).
# Set by the command (gnuplot -e): format ('png' or 'svg'), out, csv, sweep (stiffness, mass or
# damping), title; the curves as word lists series_methods, series_targets, series_colours,
# series_styles, and the integrators alone as methods, method_colours, method_targets; for the mass and damping
# sweeps (explicit Euler) lambda_safe, lambda_tight [N/m], mass [kg] and damping [N s/m].
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
set offsets graph 0.02, graph 0.02, graph 0.05, graph 0.05
xcol = sweep eq 'stiffness' ? 'k_structural_N_per_m' : sweep eq 'mass' ? 'mass_kg' : 'damping_Ns_per_m'
set xlabel (sweep eq 'stiffness' ? 'structural stiffness K [N/m] (shear and bend scaled with it)' : \
            sweep eq 'mass' ? 'mass per vertex m [kg]' : 'damping {/Symbol m} [N s/m]')
set ylabel 'largest stable time step [s]'
set title title noenhanced
set key outside right center vertical noenhanced font ',9' spacing 1.1
set grid
set pointsize 1.3

n = words(series_methods)
method(i) = word(series_methods, i)
target(i) = word(series_targets, i)
colour(i) = int(word(series_colours, i))
point(i) = int(word(series_styles, i)) == 3 ? 4 : 7
mine(i) = strcol('sweep') eq sweep && strcol('method') eq method(i) && strcol('target') eq target(i)
x(i) = mine(i) ? column(xcol) : NaN
measured(i, status) = mine(i) && strcol('status') eq status ? column('measured_dt_s') : NaN

# Predicted bounds over stiffness: lines through each sample's prediction, from the first curve
# of each integrator (the same on every backend); an infinite bound (implicit Euler) is an empty
# cell: no line and no key entry.
nm = words(methods)
predictedRow(k) = strcol('sweep') eq sweep && strcol('method') eq word(methods, k) \
                  && strcol('target') eq word(method_targets, k)
predicted(k, col) = predictedRow(k) ? column(col) : NaN
line(k, kind) = word(methods, k) eq 'implicit_euler' ? '' : word(methods, k).' predicted ('.kind.')'
# Over mass or damping (explicit Euler, λ fixed): the curve min(μ/λ, 2m/μ) of docs/physics.md.
euler(mu, lambda, m) = mu / lambda < 2 * m / mu ? mu / lambda : 2 * m / mu
eulerAt(x, lambda) = sweep eq 'mass' ? euler(real(damping), lambda, x) : euler(x, lambda, real(mass))

measuredPlots = 'for [i=1:n] csv using (x(i)):(measured(i, "bounded")) with points lc (colour(i)) pt (point(i)) title method(i)." measured ".target(i), for [i=1:n] csv using (x(i)):(measured(i, "stable_to_cap")) with points lc (colour(i)) pt (point(i) + 2) ps 1.8 notitle, NaN with points lc "black" pt 9 ps 1.8 title "stable up to the cap (no bound found)"'

if (sweep eq 'stiffness') {
    plot for [k=1:nm] csv using (predicted(k, xcol)):(predicted(k, 'predicted_tight_dt_s')) \
             with lines lc (int(word(method_colours, k))) lw 2 title line(k, 'tight, power iteration'), \
         for [k=1:nm] csv using (predicted(k, xcol)):(predicted(k, 'predicted_safe_dt_s')) \
             with lines lc (int(word(method_colours, k))) dt 2 lw 1 title line(k, 'safe, Gershgorin'), \
         @measuredPlots
} else {
    plot eulerAt(x, real(lambda_tight)) with lines lc 1 lw 2 \
             title 'explicit Euler predicted min({/Symbol m}/{/Symbol l}, 2m/{/Symbol m}), {/Symbol l} tight (power iteration)' enhanced, \
         eulerAt(x, real(lambda_safe)) with lines lc 1 dt 2 lw 1 \
             title 'explicit Euler predicted, {/Symbol l} safe (Gershgorin)' enhanced, \
         @measuredPlots
}
