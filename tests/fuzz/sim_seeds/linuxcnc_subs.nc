€G21 G17 G90 G94
o<h> sub
#<r> = #1
G0 X[#<r>] Y0
G1 Z-1 F100
G3 X#<r> Y0 I[-#<r>] J0 Z-3 P2
o<h> endsub
#<i> = 0
o1 while [#<i> LT 2]
o<h> call [3+#<i>]
#<i> = [#<i>+1]
o1 endwhile
M2
