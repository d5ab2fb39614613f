shape_set cube -desc {-sub {-box {1 1 1}}}
shape_set ball -desc {-sub {-sphere 0.2}}
shape_set floor -desc {-sub {-box {60 1 60}}}
body floor -shape floor -static 1 -init_pos {0 -0.5 0} -restitution 0.5 -friction 0.5
body c0 -shape cube -mass 1 -init_pos {-1.040247768267462 1 -1.0010820143380783} -init_rot {-0.22794021513904617 1.3276454478025475 0.33328696852410866} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c0 -y {-9.8100000000000005 * c0.mass} -gravitational 1
body c1 -shape cube -mass 1 -init_pos {0.90503434674929806 1 -0.95815839794473434} -init_rot {-0.93773548886130498 -0.94558860904619957 -1.3984885308068806} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c1 -y {-9.8100000000000005 * c1.mass} -gravitational 1
body c2 -shape cube -mass 1 -init_pos {-0.96323631463174897 1 1.0633203672689104} -init_rot {-0.65571366715808566 1.5632661213280561 -1.2075127411516187} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c2 -y {-9.8100000000000005 * c2.mass} -gravitational 1
body c3 -shape cube -mass 1 -init_pos {0.90612332977412857 1 1.0755229877644106} -init_rot {0.90974204362544775 0.16352372515739333 -1.4741674012368771} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c3 -y {-9.8100000000000005 * c3.mass} -gravitational 1
body c4 -shape cube -mass 1 -init_pos {-1.0172665244181387 2.7999999999999998 -0.94425423749991833} -init_rot {0.33560546894868892 -1.2694742393920815 1.3043290017562295} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c4 -y {-9.8100000000000005 * c4.mass} -gravitational 1
body c5 -shape cube -mass 1 -init_pos {0.92108036584379216 2.7999999999999998 -1.0432846638552022} -init_rot {-1.7377469283406266 -1.7742232404179896 1.061823269912078} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c5 -y {-9.8100000000000005 * c5.mass} -gravitational 1
body c6 -shape cube -mass 1 -init_pos {-1.0976423934658419 2.7999999999999998 1.0223886674047282} -init_rot {-0.67247097668363809 0.23859346780854862 -0.6580014060340269} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c6 -y {-9.8100000000000005 * c6.mass} -gravitational 1
body c7 -shape cube -mass 1 -init_pos {0.98223651006355417 2.7999999999999998 0.91537110023731294} -init_rot {1.4121719764812677 -0.24005019008471051 -1.5121834011503614} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c7 -y {-9.8100000000000005 * c7.mass} -gravitational 1
body c8 -shape cube -mass 1 -init_pos {-0.95365307533426269 4.5999999999999996 -1.072243507168289} -init_rot {1.06752018276504 1.3279590651922395 -0.76088777896794246} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c8 -y {-9.8100000000000005 * c8.mass} -gravitational 1
body c9 -shape cube -mass 1 -init_pos {1.0195164584906142 4.5999999999999996 -0.92552150831110946} -init_rot {1.9320834659821693 -0.13038687657051562 1.5029779813857895} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c9 -y {-9.8100000000000005 * c9.mass} -gravitational 1
body c10 -shape cube -mass 1 -init_pos {-1.0407862600687645 4.5999999999999996 0.92625821032996569} -init_rot {1.37127175072311 0.63614521934758139 0.38175841829191359} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c10 -y {-9.8100000000000005 * c10.mass} -gravitational 1
body c11 -shape cube -mass 1 -init_pos {0.98727073962540646 4.5999999999999996 0.97125006588118268} -init_rot {0.34852369079022161 -1.4021146513278384 -1.3150456126300858} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c11 -y {-9.8100000000000005 * c11.mass} -gravitational 1
body c12 -shape cube -mass 1 -init_pos {-1.020567096229765 6.4000000000000004 -0.97240968705607433} -init_rot {-0.50992020169779839 -1.9903729468675317 0.19526541236721151} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c12 -y {-9.8100000000000005 * c12.mass} -gravitational 1
body c13 -shape cube -mass 1 -init_pos {0.92539436925934537 6.4000000000000004 -1.0840414629746409} -init_rot {-1.0598456074432843 0.63985978097721885 -1.1401872152706325} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c13 -y {-9.8100000000000005 * c13.mass} -gravitational 1
body c14 -shape cube -mass 1 -init_pos {-1.0593906766250749 6.4000000000000004 0.97657302256810907} -init_rot {-1.1005087855132978 -1.5414047980341212 0.3320682210348056} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c14 -y {-9.8100000000000005 * c14.mass} -gravitational 1
body c15 -shape cube -mass 1 -init_pos {0.94652821202963111 6.4000000000000004 1.0113036372177264} -init_rot {0.095243538509347303 -0.59616709977565652 0.82132645083359357} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c15 -y {-9.8100000000000005 * c15.mass} -gravitational 1
body c16 -shape cube -mass 1 -init_pos {-0.93585925118040403 8.1999999999999993 -1.0730874001740727} -init_rot {0.41890463754333229 -0.86740690445321089 0.02563130511052103} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c16 -y {-9.8100000000000005 * c16.mass} -gravitational 1
body c17 -shape cube -mass 1 -init_pos {0.90769208660467526 8.1999999999999993 -1.0335111811615962} -init_rot {-1.9989098876322844 0.65862187701983199 -0.49023732955985988} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c17 -y {-9.8100000000000005 * c17.mass} -gravitational 1
body c18 -shape cube -mass 1 -init_pos {-0.95048360533662457 8.1999999999999993 0.92811515691190949} -init_rot {-0.44780220551020378 1.4659665729653271 1.8274133031626305} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c18 -y {-9.8100000000000005 * c18.mass} -gravitational 1
body c19 -shape cube -mass 1 -init_pos {0.99731073311972662 8.1999999999999993 0.9211866121262815} -init_rot {-0.63985084421860638 1.342283160722137 -0.13823350191135231} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c19 -y {-9.8100000000000005 * c19.mass} -gravitational 1
body c20 -shape cube -mass 1 -init_pos {-1.0814287796347339 10 -0.92906117095360841} -init_rot {-0.65096726541584604 0.42458699221213436 -1.5493416117672352} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c20 -y {-9.8100000000000005 * c20.mass} -gravitational 1
body c21 -shape cube -mass 1 -init_pos {1.0087840895037448 10 -0.95584028230113804} -init_rot {1.4632614674392106 -1.4131954951671357 -1.5864757061347452} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c21 -y {-9.8100000000000005 * c21.mass} -gravitational 1
body c22 -shape cube -mass 1 -init_pos {-1.0018890641024463 10 0.90583591156230936} -init_rot {0.3794438034980252 -1.1766180953390954 -1.1887880879915529} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c22 -y {-9.8100000000000005 * c22.mass} -gravitational 1
body c23 -shape cube -mass 1 -init_pos {1.0688251752098006 10 0.91231327537019102} -init_rot {-0.0030772619145895685 -1.0061320952271791 -0.69142388425267765} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c23 -y {-9.8100000000000005 * c23.mass} -gravitational 1
body c24 -shape cube -mass 1 -init_pos {-1.0994167828830532 11.800000000000001 -1.0409115717395909} -init_rot {1.9475564790022371 -1.046669136039351 0.93358591056408846} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c24 -y {-9.8100000000000005 * c24.mass} -gravitational 1
body c25 -shape cube -mass 1 -init_pos {1.0924393774288825 11.800000000000001 -0.93690884140564035} -init_rot {0.77690789679441119 -1.1572156151336879 0.071376274385142935} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c25 -y {-9.8100000000000005 * c25.mass} -gravitational 1
body c26 -shape cube -mass 1 -init_pos {-0.910066002362938 11.800000000000001 1.0391947738613192} -init_rot {1.6186589451756079 0.59156970156488153 -0.61879142287910649} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c26 -y {-9.8100000000000005 * c26.mass} -gravitational 1
body c27 -shape cube -mass 1 -init_pos {0.91309957061546654 11.800000000000001 0.94412557327033719} -init_rot {-1.4505069902786325 0.97718369217110812 -0.61323736330689926} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c27 -y {-9.8100000000000005 * c27.mass} -gravitational 1
body c28 -shape cube -mass 1 -init_pos {-0.98446714949919711 13.6 -1.0663294135689849} -init_rot {-1.8481131982416312 1.2687068161343551 1.2498594108821783} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c28 -y {-9.8100000000000005 * c28.mass} -gravitational 1
body c29 -shape cube -mass 1 -init_pos {0.93768713212147592 13.6 -1.0253875207552439} -init_rot {0.97676854527411106 -1.2550088943039159 -0.34480877024622658} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c29 -y {-9.8100000000000005 * c29.mass} -gravitational 1
simulator -finish 5
