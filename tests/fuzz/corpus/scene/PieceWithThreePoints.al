shape_set s -desc {-sub {-vertices {{0 0 0} {1 0 0} {0 1 0}}}}
