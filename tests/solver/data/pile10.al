# Ten cubes at random rotations dropped in a column onto a static floor
# (issue 14): they pile up and come to rest above the floor.  The floor is
# 60 wide: a cube struck at the speed of its fall (up to 14 m/s) is thrown
# metres aside.
shape_set cube -desc {-sub {-box {1 1 1}}}
shape_set floor -desc {-sub {-box {60 1 60}}}
body floor -shape floor -static 1 -init_pos {0 -0.5 0} -restitution 0.5 -friction 0.5
body c0 -shape cube -mass 1 -init_pos {-0.4718 1.0000 0.2431} -init_rot {-1.3302 -1.8812 -0.0987} -restitution 0.5 -friction 0.5
force -body c0 -y {-9.81 * c0.mass} -gravitational 1
body c1 -shape cube -mass 1 -init_pos {0.1901 2.5000 -0.2364} -init_rot {1.4754 -0.7817 -1.7829} -restitution 0.5 -friction 0.5
force -body c1 -y {-9.81 * c1.mass} -gravitational 1
body c2 -shape cube -mass 1 -init_pos {-0.4579 4.0000 -0.3321} -init_rot {1.6036 -1.1427 -0.2467} -restitution 0.5 -friction 0.5
force -body c2 -y {-9.81 * c2.mass} -gravitational 1
body c3 -shape cube -mass 1 -init_pos {-0.4204 5.5000 0.0616} -init_rot {1.9424 -0.3329 -0.5549} -restitution 0.5 -friction 0.5
force -body c3 -y {-9.81 * c3.mass} -gravitational 1
body c4 -shape cube -mass 1 -init_pos {-0.4524 7.0000 -0.1955} -init_rot {1.5029 0.8661 2.5832} -restitution 0.5 -friction 0.5
force -body c4 -y {-9.81 * c4.mass} -gravitational 1
body c5 -shape cube -mass 1 -init_pos {-0.0736 8.5000 0.1290} -init_rot {-0.0321 0.2430 -0.2504} -restitution 0.5 -friction 0.5
force -body c5 -y {-9.81 * c5.mass} -gravitational 1
body c6 -shape cube -mass 1 -init_pos {0.1069 10.0000 0.1605} -init_rot {0.1188 0.2574 0.5390} -restitution 0.5 -friction 0.5
force -body c6 -y {-9.81 * c6.mass} -gravitational 1
body c7 -shape cube -mass 1 -init_pos {-0.0569 11.5000 -0.3382} -init_rot {-0.1883 0.0779 -0.2490} -restitution 0.5 -friction 0.5
force -body c7 -y {-9.81 * c7.mass} -gravitational 1
body c8 -shape cube -mass 1 -init_pos {0.3818 13.0000 -0.4926} -init_rot {-0.3139 1.6086 -0.2051} -restitution 0.5 -friction 0.5
force -body c8 -y {-9.81 * c8.mass} -gravitational 1
body c9 -shape cube -mass 1 -init_pos {-0.4884 14.5000 -0.0235} -init_rot {-0.5273 -0.5250 -1.2211} -restitution 0.5 -friction 0.5
force -body c9 -y {-9.81 * c9.mass} -gravitational 1
simulator -finish 8
