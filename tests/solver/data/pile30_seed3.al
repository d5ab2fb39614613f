shape_set cube -desc {-sub {-box {1 1 1}}}
shape_set ball -desc {-sub {-sphere 0.2}}
shape_set floor -desc {-sub {-box {60 1 60}}}
body floor -shape floor -static 1 -init_pos {0 -0.5 0} -restitution 0.5 -friction 0.5
body c0 -shape cube -mass 1 -init_pos {-1.0858550239097886 1 -0.9320101915063268} -init_rot {-1.5146856826814779 0.27724530316035034 -0.25175223882035636} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c0 -y {-9.8100000000000005 * c0.mass} -gravitational 1
body c1 -shape cube -mass 1 -init_pos {0.90374960209691402 1 -1.0918738524836682} -init_rot {-1.0084467928789156 -1.6257940176395074 0.77929462906048608} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c1 -y {-9.8100000000000005 * c1.mass} -gravitational 1
body c2 -shape cube -mass 1 -init_pos {-1.070925970513845 1 0.99063445993032462} -init_rot {-1.137691949820943 -0.5843797081350468 -0.029456314932317484} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c2 -y {-9.8100000000000005 * c2.mass} -gravitational 1
body c3 -shape cube -mass 1 -init_pos {1.0826602905798173 1 1.0531652749061575} -init_rot {1.8945930847514925 -0.39055743044311875 0.2110877944297167} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c3 -y {-9.8100000000000005 * c3.mass} -gravitational 1
body c4 -shape cube -mass 1 -init_pos {-1.0387278745750186 2.7999999999999998 -0.98267600556401824} -init_rot {-0.90031956933396518 -0.1815689400240148 1.0306609827509607} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c4 -y {-9.8100000000000005 * c4.mass} -gravitational 1
body c5 -shape cube -mass 1 -init_pos {1.0635141455000414 2.7999999999999998 -1.0484829416355881} -init_rot {1.5722604256327801 0.8736881011984976 -1.9175419910472038} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c5 -y {-9.8100000000000005 * c5.mass} -gravitational 1
body c6 -shape cube -mass 1 -init_pos {-1.0714565340440723 2.7999999999999998 0.96506123545916678} -init_rot {1.235716799183594 -0.40403617467195652 -0.30119356012158649} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c6 -y {-9.8100000000000005 * c6.mass} -gravitational 1
body c7 -shape cube -mass 1 -init_pos {0.98274373673332005 2.7999999999999998 1.0574277001271681} -init_rot {0.85426299139656203 -1.9075297253564327 -0.73693100621453067} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c7 -y {-9.8100000000000005 * c7.mass} -gravitational 1
body c8 -shape cube -mass 1 -init_pos {-0.98744598071060519 4.5999999999999996 -0.95036851263284028} -init_rot {0.43849465648572483 -1.1865818842390619 0.61452341029205027} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c8 -y {-9.8100000000000005 * c8.mass} -gravitational 1
body c9 -shape cube -mass 1 -init_pos {1.0325372532410795 4.5999999999999996 -0.92578558984276593} -init_rot {1.2449110255422888 -0.50350108716825259 -1.6991995447737891} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c9 -y {-9.8100000000000005 * c9.mass} -gravitational 1
body c10 -shape cube -mass 1 -init_pos {-0.94788430192482609 4.5999999999999996 0.91275396035990575} -init_rot {1.3641646397430778 0.77053498857396585 -0.21639823682272286} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c10 -y {-9.8100000000000005 * c10.mass} -gravitational 1
body c11 -shape cube -mass 1 -init_pos {0.97246809175061877 4.5999999999999996 1.0032189239146041} -init_rot {-0.17067129840446049 1.233448932590981 -0.73486186499783734} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c11 -y {-9.8100000000000005 * c11.mass} -gravitational 1
body c12 -shape cube -mass 1 -init_pos {-0.93124258092727508 6.4000000000000004 -1.002141748849855} -init_rot {0.16047840597093899 1.3045122991993967 0.086417347496195784} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c12 -y {-9.8100000000000005 * c12.mass} -gravitational 1
body c13 -shape cube -mass 1 -init_pos {0.92851986929053187 6.4000000000000004 -1.0395472772856462} -init_rot {1.2280906999881149 -0.72201985868476082 -1.9150970389781667} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c13 -y {-9.8100000000000005 * c13.mass} -gravitational 1
body c14 -shape cube -mass 1 -init_pos {-1.0035108394598831 6.4000000000000004 0.90520525335569291} -init_rot {0.022296231914254783 1.6721200900851643 -1.1721354568408207} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c14 -y {-9.8100000000000005 * c14.mass} -gravitational 1
body c15 -shape cube -mass 1 -init_pos {1.0851465568908942 6.4000000000000004 0.95546460980887349} -init_rot {-1.2957515388736724 1.9612047543300886 0.77060246570045532} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c15 -y {-9.8100000000000005 * c15.mass} -gravitational 1
body c16 -shape cube -mass 1 -init_pos {-0.94957199398757453 8.1999999999999993 -1.0767566818951966} -init_rot {-1.6559971382954952 0.66249843123564611 -0.68171456765233374} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c16 -y {-9.8100000000000005 * c16.mass} -gravitational 1
body c17 -shape cube -mass 1 -init_pos {0.97233012353726755 8.1999999999999993 -0.99477780006326821} -init_rot {-0.30108019685010734 1.2791229159820134 0.28513898033573559} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c17 -y {-9.8100000000000005 * c17.mass} -gravitational 1
body c18 -shape cube -mass 1 -init_pos {-0.92377785194076978 8.1999999999999993 1.0601207021847479} -init_rot {-0.60029911171449046 1.0909547347060893 1.5859866325374004} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c18 -y {-9.8100000000000005 * c18.mass} -gravitational 1
body c19 -shape cube -mass 1 -init_pos {1.0571460668888863 8.1999999999999993 0.95668147442087836} -init_rot {1.5276337911988986 0.18153046774942849 1.3120884682949452} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c19 -y {-9.8100000000000005 * c19.mass} -gravitational 1
body c20 -shape cube -mass 1 -init_pos {-1.0532615981440958 10 -1.0594244703312559} -init_rot {1.8333449352392339 1.0646110251286052 -1.246996606838916} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c20 -y {-9.8100000000000005 * c20.mass} -gravitational 1
body c21 -shape cube -mass 1 -init_pos {0.99387626250011818 10 -0.99949395674794028} -init_rot {-1.3105484019137237 -0.80637258391088218 -0.92477068417927422} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c21 -y {-9.8100000000000005 * c21.mass} -gravitational 1
body c22 -shape cube -mass 1 -init_pos {-0.92262037450051426 10 1.0006510580636225} -init_rot {0.28895047979241761 -0.63032165246343852 0.43858285907062111} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c22 -y {-9.8100000000000005 * c22.mass} -gravitational 1
body c23 -shape cube -mass 1 -init_pos {0.92412347355356406 10 0.90778361957707332} -init_rot {1.9999018554979306 -0.92820898032362864 -0.97117448779837323} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c23 -y {-9.8100000000000005 * c23.mass} -gravitational 1
body c24 -shape cube -mass 1 -init_pos {-1.0446716906405347 11.800000000000001 -1.0496516978493562} -init_rot {1.5909481175719971 1.340985242723467 -1.4147351102207038} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c24 -y {-9.8100000000000005 * c24.mass} -gravitational 1
body c25 -shape cube -mass 1 -init_pos {1.0990886350000382 11.800000000000001 -1.0288541817126586} -init_rot {0.18852301727563203 -0.032737807305406319 -1.4813664638830986} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c25 -y {-9.8100000000000005 * c25.mass} -gravitational 1
body c26 -shape cube -mass 1 -init_pos {-0.92798930741460661 11.800000000000001 0.94367958041651678} -init_rot {1.2973255780905122 1.9931324988952488 1.9651828838233216} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c26 -y {-9.8100000000000005 * c26.mass} -gravitational 1
body c27 -shape cube -mass 1 -init_pos {0.9315339510915962 11.800000000000001 0.99413319629114016} -init_rot {0.82972602722753797 -0.6399762990505542 0.78699995117697252} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c27 -y {-9.8100000000000005 * c27.mass} -gravitational 1
body c28 -shape cube -mass 1 -init_pos {-0.95031845602839626 13.6 -0.93659292779439718} -init_rot {1.3908878171267753 -1.6737158297020629 -0.76926508667416549} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c28 -y {-9.8100000000000005 * c28.mass} -gravitational 1
body c29 -shape cube -mass 1 -init_pos {1.0121972534731691 13.6 -0.91602791684087592} -init_rot {-1.6204746641599503 -0.37640406309935281 0.15385476699049327} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c29 -y {-9.8100000000000005 * c29.mass} -gravitational 1
simulator -finish 5
