%
O4000 (circular pocket 40 dia, 10 mm cutter: a spiral of half circles);
G21 G17 G90 G40 G80;
T5 M06;
G00 G54 X50. Y50.;
G00 G43 H5 Z5.;
S4000 M03;
G01 Z-3. F150.;
#1 = 2.;  (step over per half turn)
#2 = 15.; (last path radius: 20 - 5)
#3 = 0;   (radius reached)
#5 = 1.;  (1: on the +X side, -1: on the -X side)
G91;
WH [#3 LT #2] DO1;
#4 = #3 + #1;
IF [#4 GT #2] TH #4 = #2;
#6 = #3 + #4;
G03 X[-#5 * #6] Y0. I[-#5 * #6 / 2.] J0.;
#3 = #4;
#5 = -#5;
EN1;
G03 X0. Y0. I[-#5 * #3] J0.; (a full turn at the wall)
G90 G01 X50. Y50.;
G00 Z5.;
M30;
%
