# Plots the CSV of bench_dynamics_flight (six panels: horizontal position, altitude, attitude,
# rotor speeds, battery and power, ground track). Usage:
#   gnuplot -e "csv='dynamics_flight.csv'; png='dynamics_flight.png'" plot_flight.gp
if (!exists("csv")) csv = 'dynamics_flight.csv'
if (!exists("png")) png = 'dynamics_flight.png'
set terminal pngcairo size 1400,930 font "DejaVu Sans,10" linewidth 1.4
set output png
set datafile separator ","
set key autotitle columnhead
set grid lc rgb "#dddddd"
set key top right font ",10" samplen 2 spacing 1.1
set multiplot layout 3,2 title "Scripted flight of the 3DR Iris model (CVODE, virtual time, closed loop): take-off, legs, turns, landing; wind 5 m/s from 240° with Dryden turbulence" font ",12"

set title "Horizontal position"
set xlabel "time (s)"; set ylabel "m"
plot csv using 1:2 with lines lw 2 lc rgb "#1f77b4" title "x (east)", \
     csv using 1:5 with lines dt 2 lc rgb "#1f77b4" title "x reference", \
     csv using 1:3 with lines lw 2 lc rgb "#d62728" title "y (north)", \
     csv using 1:6 with lines dt 2 lc rgb "#d62728" title "y reference"

set title "Altitude"
set ylabel "m"
plot csv using 1:4 with lines lw 2 lc rgb "#2ca02c" title "z", \
     csv using 1:7 with lines dt 2 lc rgb "#2ca02c" title "z reference", \
     csv using 1:($20*2) with filledcurves y1=0 fs transparent solid 0.15 lc rgb "#7f7f7f" title "on ground"

set title "Attitude"
set ylabel "roll, pitch (deg)"; set y2label "yaw from east (deg)"
set y2tics 90; set ytics nomirror; set y2range [-45:405]
plot csv using 1:8 with lines lw 1.5 lc rgb "#9467bd" title "roll", \
     csv using 1:9 with lines lw 1.5 lc rgb "#ff7f0e" title "pitch", \
     csv using 1:10 axes x1y2 with lines lw 1.5 lc rgb "#17becf" title "yaw (right axis)", \
     csv using 1:11 axes x1y2 with lines dt 2 lc rgb "#17becf" title "yaw reference"
unset y2tics; unset y2label; set ytics mirror; set autoscale y2

set title "Rotor speeds"
set ylabel "rad/s"
plot csv using 1:12 with lines lw 1 title "0 front-right (CCW)", \
     csv using 1:13 with lines lw 1 title "1 rear-left (CCW)", \
     csv using 1:14 with lines lw 1 title "2 front-left (CW)", \
     csv using 1:15 with lines lw 1 title "3 rear-right (CW)"

set title "Battery"
set ylabel "state of charge (%)"; set y2label "electrical power (W)"
set y2tics autofreq; set ytics nomirror
plot csv using 1:16 with lines lw 2 lc rgb "#2ca02c" title "state of charge", \
     csv using 1:18 axes x1y2 with lines lw 1 lc rgb "#d62728" title "power (right axis)"
unset y2tics; unset y2label; set ytics mirror

set title "Ground track (top view)"
set xlabel "x east (m)"; set ylabel "y north (m)"
set size ratio -1
plot csv using 2:3 with lines lw 2 lc rgb "#1f77b4" title "flown", \
     csv using 5:6 with lines dt 2 lc rgb "#7f7f7f" title "reference"
unset multiplot
