%
O1000 (Two bores milled by a helix - Fanuc 0i-MD style);
(tool 1: 10 mm end mill, work offset G54);
G21 G17 G90 G40 G80;
T1 M06;
G00 G54 X0. Y0.;
G00 G43 H1 Z25.;
S3000 M03;
(22 mm bore at X30 Y20, 10 deep, 3 mm pitch);
G65 P9100 X30. Y20. I6. C3. K10. F400.;
(16 mm bore at X-25 Y10, clockwise);
G65 P9100 X-25. Y10. I3. C2. K4. E2. F300. R5.;
G00 Z25.;
M05;
M30;
O9100 (helical bore: X Y centre, I helix radius, C pitch, K depth);
(E: 2 = clockwise, 3 = counterclockwise; R: clearance, F: feed);
IF [#4 EQ #0] THEN #3000 = 1 (HELIX RADIUS I MISSING);
IF [#8 EQ #0] TH #8 = 3.;
IF [#18 EQ #0] TH #18 = 2.;
#12 = FUP[#6 / #3];   (number of turns)
#13 = #6 / #12;       (depth per turn)
G90 G00 X#24 Y#25;
Z#18;
G01 Z0. F#9;
G91 G01 X#4;
#14 = 1;
WH [[#14 LT #12] OR [#14 EQ #12]] DO1;
G#8 X0. Y0. I-#4 J0. Z-#13;
#14 = #14 + 1;
EN1;
G#8 X0. Y0. I-#4 J0.; (flat turn at the bottom)
G01 X-#4;
G90 G00 Z#18;
M99;
%
