set terminal svg size 720,440 dynamic font 'sans,11' background '#ffffff'
set output 'tessellation.svg'
set title 'Curved walls: decomposition time against geometric error (labels: tolerance [m])'
set xlabel 'decomposition time [ms]'
set ylabel 'largest sagitta [mm]'
set grid
set key outside right top
set logscale x
set format x '%g'
set format y '%g'
set logscale y
set offsets graph 0.1, graph 0.1, graph 0.1, graph 0.1
plot 'tessellation.dat' using 2:3 with linespoints pt 7 title 'curved-walls', '' using 2:3:1 with labels offset 0,1 notitle
