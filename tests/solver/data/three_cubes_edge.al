# Three cubes, each turned a little about a horizontal axis, dropped on a
# static floor: they land on an edge (issue 14).
shape_set cube -desc {-sub {-box {1 1 1}}}
shape_set floor -desc {-sub {-box {20 1 20}}}
body floor -shape floor -static 1 -init_pos {0 -0.5 0} -restitution 0.5 -friction 0.5
body c1 -shape cube -mass 1 -init_pos {-3 2 0} -init_rot {0.1 0 0} -restitution 0.5 -friction 0.5
body c2 -shape cube -mass 1 -init_pos {0 2 0} -init_rot {0 0 0.2} -restitution 0.5 -friction 0.5
body c3 -shape cube -mass 1 -init_pos {3 2 0} -init_rot {0.3 0 0.15} -restitution 0.5 -friction 0.5
force -body c1 -y {-9.81 * c1.mass} -gravitational 1
force -body c2 -y {-9.81 * c2.mass} -gravitational 1
force -body c3 -y {-9.81 * c3.mass} -gravitational 1
simulator -finish 3
