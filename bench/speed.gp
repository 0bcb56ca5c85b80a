# `clothsim bench speed`: vertex-steps per second against the vertex count, log-log, one line
# per target (backend and precision, or the baseline) and integrator.
# Set by the command (gnuplot -e): format ('png' or 'svg'), out, csv, title, and series: the
# curves as words 'target:method:variant' (e.g. 'baseline:explicit_euler:
# gpu_float:explicit_euler:16x16/global/per-step'; the variant is empty for the CPU).
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
variant(i) = rest(i)[strstrt(rest(i), ':') + 1:]
mine(i) = strcol('target') eq target(i) && strcol('method') eq method(i) && \
          strcol('gpu_variant') eq variant(i)
y(i) = mine(i) ? column('vertex_steps_per_s') : NaN
width(i) = target(i) eq 'baseline' ? 3 : 2
label(i) = target(i) eq 'baseline' ? 'baseline (1x, one thread, double)' : \
           target(i).' '.method(i).(variant(i) eq '' ? '' : ' '.variant(i))

plot for [i=1:n] csv using (mine(i) ? column('vertices') : NaN):(y(i)) \
     with linespoints lw width(i) pt (i + 4) title label(i)
