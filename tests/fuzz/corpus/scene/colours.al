# Render test scene: coloured boxes and balls, one spinning, one falling,
# two lights and a view element.
simulator -finish 1 -frames 10
shape_set cube -desc {-box {2 2 2}}
shape_set ball -desc {-sub {-sphere 1}}
shape_set dumbbell -desc {-sub {-pos {-1.2 0 0} -sphere 0.5} -sub {-pos {1.2 0 0} -sphere 0.5 -color gold} -sub {-box {2.4 0.3 0.3}}}
body c1 -shape cube -init_pos {-3 0 0} -color red -init_drot {0 1 0}
body b1 -shape ball -init_pos {0 0 0} -color #3366cc -init_dpos {0 -1 0}
body d1 -shape dumbbell -init_pos {3 0 0} -color {0.2 0.6 0.3} -init_drot {0 0 2}
body g -shape cube -init_pos {0 -3 0} -static 1 -color lightgray
lightsource key -type point -pos {-6 8 10} -intensity 0.8
lightsource fill -type directional -dir {1 -0.5 -1} -intensity 0.4
