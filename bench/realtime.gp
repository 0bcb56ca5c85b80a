# `clothsim bench realtime`: wall time per simulated second against N (the sheet is N x N),
# log-log, one line per integrator (colour) and target (cpu double solid with filled circles, cpu
# float dashed with triangles, gpu float dotted with squares), through every trial that ran the
# whole simulated time; trials cut off early are open diamonds at the rate they had reached; the
# frontier (the largest real-time N) is circled; the horizontal line at 1 is real time.
# Set by the command (gnuplot -e): format ('png' or 'svg'), out, csv (the trials CSV),
# frontier_csv, title, subtitle (the material's numbers); the curves as word lists series_methods, series_targets, series_colours,
# series_styles (1 cpu double, 2 cpu float, 3 gpu float).
if (format eq 'png') {
    set terminal pngcairo size 1300,850 enhanced font ',11'
} else {
    set terminal svg size 1300,850 dynamic enhanced font ',11'
}
set output out
set datafile separator ','
set datafile columnheaders
set xlabel 'N (the sheet is N x N vertices)'
set ylabel 'wall time per simulated second'
set title title."\n".subtitle noenhanced
set key outside right center vertical noenhanced font ',9' spacing 1.1
set grid
set pointsize 1.2

n = words(series_methods)
method(i) = word(series_methods, i)
target(i) = word(series_targets, i)
colour(i) = int(word(series_colours, i))
style(i) = int(word(series_styles, i))
dash(i) = style(i) == 1 ? 1 : style(i) == 2 ? 2 : 3
point(i) = style(i) == 1 ? 7 : style(i) == 2 ? 9 : 5
mine(i) = strcol('method') eq method(i) && strcol('target') eq target(i)
ran(i) = mine(i) && (strcol('status') eq 'real_time' || strcol('status') eq 'too_slow')
cut(i) = mine(i) && strcol('status') eq 'cut_off'

# Each curve's rows gathered into datablocks of its own: completed trials ($ran1, ...), trials
# cut off ($cut1, ...) and its frontier ($best1, ...); rows of other curves between them would
# otherwise break its line. Each starts with a row of NaN, so that it exists even when empty.
set samples 2
do for [i=1:n] {
    eval sprintf('set table $ran%d', i)
    plot '+' using (NaN):(NaN) every ::0::0 with table, \
         csv using (column('n')):(column('wall_per_sim_s')) with table if (ran(i))
    eval sprintf('set table $cut%d', i)
    plot '+' using (NaN):(NaN) every ::0::0 with table, \
         csv using (column('n')):(column('wall_per_sim_s')) with table if (cut(i))
    eval sprintf('set table $best%d', i)
    plot '+' using (NaN):(NaN) every ::0::0 with table, \
         frontier_csv using (column('n')):(column('wall_per_sim_s')) with table \
             if (mine(i) && column('n') > 0)
    unset table
}
set logscale x 2
set logscale y 10
set format y '%g'
set datafile separator whitespace
set datafile nocolumnheaders
plot 1 with lines lc 'black' lw 2 dt 1 title 'real time (1 s per simulated second)', \
     for [i=1:n] sprintf('$ran%d', i) using 1:2 with linespoints lw 2 lc colour(i) dt dash(i) \
         pt point(i) title method(i).' '.target(i), \
     for [i=1:n] sprintf('$cut%d', i) using 1:2 with points lc colour(i) pt 12 notitle, \
     for [i=1:n] sprintf('$best%d', i) using 1:2 with points lc colour(i) pt 6 ps 3 notitle, \
     NaN with points lc 'black' pt 12 title 'cut off early (rate reached)', \
     NaN with points lc 'black' pt 6 ps 3 title 'frontier: largest real-time N'
