set s [string repeat a 10000000]
set m [string map [list a [string repeat b 1000]] $s]
