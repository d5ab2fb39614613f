# The double pendulum of the dissertation's Figure 4.6 (file pend.al in the
# language viewer): two rods hanging from the origin by links, pulled down by
# forces of -10 * mass, and a ball thrown at them.  Text as printed, with
# the OCR errors of the scan corrected (shape_set, -init_pos, -init_dpos,
# body); `index` is the old Tcl name of lindex.

simulator -finish 5 -step 0.1

set faces1 {}
set faces2 {}
foreach ff {
  {{0 0 0} {0 1 0} {0 1 1} {0 0 1}}
  {{1 0 0} {1 1 0} {1 1 1} {1 0 1}}
  {{0 0 0} {1 0 0} {1 0 1} {0 0 1}}
  {{0 1 0} {1 1 0} {1 1 1} {0 1 1}}
  {{0 0 0} {1 0 0} {1 1 0} {0 1 0}}
  {{0 0 1} {1 0 1} {1 1 1} {0 1 1}} } {
  set f1 "-color black"
  set f2 "-color black"
  foreach pp $ff {
    set x [expr {[index $pp 0] - 0.5}]
    set y [expr {[index $pp 1] - 0.5}]
    set z [expr {[index $pp 2] - 0.5}]
    lappend f1 [list $x $y $z]
    lappend f2 [list [expr {$x * 10}] \
                    [expr {$y * 1.1}] \
                    [expr {$z * 1.1}]]
  }
  set faces1 "$faces1 -face \{$f1\}"
  set faces2 "$faces2 -face \{$f2\}"
}

shape_set ss1 -desc { -sub {-pos {0 0 0} -sphere 0.5}}
shape_set box -desc $faces1
shape_set rod -desc $faces2

body b1 -shape rod -artbody b -init_pos {-5 0 0} -ct 0 -mass 10
body b2 -shape rod -artbody b -init_pos {-15 0 0} -ct 0 -mass 10
link -body1 b1 -offset1 {5 0 0} -x 0 -y 0 -z 0 -tightness 5000
link -body1 b2 -offset1 {5 0 0} -body2 b1 -offset2 {-5 0 0} -tightness 5000

force -torque 0 -body b1 -x 0 -y {-10 * b1.mass} -z 0
force -torque 0 -body b2 -x 0 -y {-10 * b2.mass} -z 0

body b3 -shape ss1 -init_pos {10.1 -17 0} -init_dpos {-3 0 0} -ct 1
