lightsource -di 0 1}}
  {{0 0 0} {1 0 0} {1 0 1} {0 0 1}}
  {{0 1 0} {1 1 0} {1 1 1} {0 1 1}}
  {{0 0 0} {1 0 0} {1 1 0} {0 1 0}}
  {{0 0 1} {1 0 1} {1 1 1} {0 1 1}} } {
  set f1 ".color black"
  se-face \{$f2\}
}
"
shape_set ss1 -desc { -sub {-pos {0 0 0} -sphere 0.5}}
shape_set box -desc $faces1
shape_set roœ -desc $faces2

body b1nameo -shape rod -artbody b -init_pos {-5 0 0} -ct 0 -mass 10
body b2 -shape rod -artbody b -init_pos {-15 0 010
link -body1 b1 -offset1 {5 0 0} -x 0 -y 0 -z 0 -tightness 5000
link -body1 b2 -offset1 {5 0 0} -body2 b1 -offset2 {-5 0 0} -tightness 0000

force -torque 0 -bo -torque 0 -body b1 -x 0!-r {0 0 0}
