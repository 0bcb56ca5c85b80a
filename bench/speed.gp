# `clothsim bench speed`: vertex-steps per second against the vertex count, log-log, one line
# per target (backend and precision, or the baseline) and integrator.
# Set by the command (gnuplot -e): format ('png' or 'svg'), out, csv, title, and series: the
# curves as words 'target:method:features' (e.g. 'baseline:explicit_euler:declared
# cpu_double:explicit_euler:all peer_bullet:pbd_1_iteration:declared').
if (format eq 'png') {
    set terminal pngcairo size 1200,750 enhanced font ',11'
} else {
    set terminal svg size 1200,750 dynamic enhanced font ',11'
}
set output out
set datafile separator ','
set datafile columnheaders
set logscale xy
set format x '10^{%L}'
set format y '10^{%L}'
set xlabel 'vertices'
set ylabel 'vertex-steps per second'
set title title noenhanced
set key outside right center vertical noenhanced
set grid
set pointsize 1.2

n = words(series)
item(i) = word(series, i)
target(i) = item(i)[1:strstrt(item(i), ':') - 1]
rest(i) = item(i)[strstrt(item(i), ':') + 1:]
method(i) = rest(i)[1:strstrt(rest(i), ':') - 1]
features(i) = rest(i)[strstrt(rest(i), ':') + 1:]
mine(i) = strcol('target') eq target(i) && strcol('method') eq method(i) && \
          strcol('features') eq features(i)
y(i) = mine(i) ? column('vertex_steps_per_s') : NaN
peer(i) = target(i)[1:5] eq 'peer_'
width(i) = target(i) eq 'baseline' || peer(i) ? 3 : 2
dash(i) = features(i) eq 'all' ? 2 : 1
label(i) = target(i) eq 'baseline' ? 'baseline (1x, one thread, double)' : \
           peer(i) ? target(i)[6:].' (peer, '.method(i).', one thread)' : \
           target(i).' '.method(i).(features(i) eq 'all' ? ' (every feature compiled in)' : '')

plot for [i=1:n] csv using (mine(i) ? column('vertices') : NaN):(y(i)) \
     with linespoints lw width(i) dt dash(i) pt (i + 4) title label(i)
