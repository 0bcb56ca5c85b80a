# `clothsim bench speed`: vertex-steps per second against the vertex count, log-log, one line
# per target (backend and precision, or the baseline) and integrator.
# Set by the command (gnuplot -e): format ('png' or 'svg'), out, csv, title, and series: the
# curves as words 'target:method:features:variant' (e.g. 'baseline:explicit_euler:declared:
# cpu_double:explicit_euler:all: gpu_float:explicit_euler:declared:16x16/global/per-step'; the
# variant is the GPU's, empty elsewhere).
if (format eq 'png') {
    set terminal pngcairo size 1100,850 enhanced font ',11'
} else {
    set terminal svg size 1100,850 dynamic enhanced font ',11'
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
set key outside bottom center horizontal maxcols 2 noenhanced
set grid
set pointsize 1.2

n = words(series)
item(i) = word(series, i)
target(i) = item(i)[1:strstrt(item(i), ':') - 1]
rest(i) = item(i)[strstrt(item(i), ':') + 1:]
method(i) = rest(i)[1:strstrt(rest(i), ':') - 1]
tail(i) = rest(i)[strstrt(rest(i), ':') + 1:]
features(i) = tail(i)[1:strstrt(tail(i), ':') - 1]
variant(i) = tail(i)[strstrt(tail(i), ':') + 1:]
mine(i) = strcol('target') eq target(i) && strcol('method') eq method(i) && \
          strcol('features') eq features(i) && strcol('gpu_variant') eq variant(i)
peer(i) = target(i)[1:5] eq 'peer_'
width(i) = target(i) eq 'baseline' || peer(i) ? 3 : 2
dash(i) = features(i) eq 'all' ? 2 : 1
# One colour per target, so a scene with every feature compiled in (dashed) is drawn in its
# declared twin's colour.
colour(i) = target(i) eq 'baseline' ? 1 : target(i) eq 'cpu_float' ? 2 : \
            target(i) eq 'cpu_double' ? 3 : target(i) eq 'gpu_float' ? 4 : 8
label(i) = target(i) eq 'baseline' ? 'baseline (1x, one thread, double)' : \
           peer(i) ? target(i)[6:].' (peer, '.method(i).', one thread)' : \
           target(i).' '.method(i).(variant(i) eq '' ? '' : ' '.variant(i)). \
           (features(i) eq 'all' ? ' (every feature compiled in)' : '')

# Each curve's rows first gathered into a datablock of its own ($curve1, ...): rows of other
# curves between them would otherwise break its line. Then drawn from there, log-log.
unset logscale
do for [i=1:n] {
    eval sprintf('set table $curve%d', i)
    plot csv using (column('vertices')):(column('vertex_steps_per_s')) with table if (mine(i))
    unset table
}
set logscale xy
set datafile separator whitespace
set datafile nocolumnheaders
plot for [i=1:n] sprintf('$curve%d', i) using 1:2 \
     with linespoints lw width(i) lc colour(i) dt dash(i) pt (i + 4) title label(i)
