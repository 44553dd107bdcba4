%
O6200 (FINISH A 40 MM BORE AT X30 Y30 WITH G41, TANGENT ENTRY AND EXIT)
(cutter radius in D3; the bore is 10 deep, roughed before)
G21 G17 G90 G40 G80
T3 M06
G00 G54 X30. Y30.
G00 G43 H3 Z5.
S4500 M03
G01 Z-10. F300.
G41 D3 G01 X40. Y20. F400. (start-up)
G03 X50. Y30. R10. (entry arc)
G03 X50. Y30. I-20. J0. (the bore)
G03 X40. Y40. R10. (exit arc)
G40 G01 X30. Y30. (cancel at the centre)
G00 Z5.
M30
%
