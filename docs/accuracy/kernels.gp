set terminal svg size 720,440 dynamic font 'sans,11' background '#ffffff'
set output 'kernels.svg'
set title 'Visibility kernels: time against error (0 errors drawn at 1e-4)'
set xlabel 'median traversal time per view [µs]'
set ylabel 'errors per view (cells + mask vertices > 0.5 px + drawings)'
set grid
set key outside right top
set logscale x
set format x '%g'
set format y '%g'
set logscale y
set offsets graph 0.1, graph 0.1, graph 0.1, graph 0.1
plot 'kernels.dat' using 2:3 with points pt 7 ps 1.5 notitle, '' using 2:3:1 with labels offset 0,1 notitle
