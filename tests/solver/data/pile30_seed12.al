shape_set cube -desc {-sub {-box {1 1 1}}}
shape_set ball -desc {-sub {-sphere 0.2}}
shape_set floor -desc {-sub {-box {60 1 60}}}
body floor -shape floor -static 1 -init_pos {0 -0.5 0} -restitution 0.5 -friction 0.5
body c0 -shape cube -mass 1 -init_pos {-1.0107556509247906 1 -0.92532256852183259} -init_rot {-1.6542628982446017 0.89440721602527384 -0.59808690844608936} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c0 -y {-9.8100000000000005 * c0.mass} -gravitational 1
body c1 -shape cube -mass 1 -init_pos {0.90679283374542119 1 -1.0409126338595192} -init_rot {-1.6699023609669679 0.90381665151282142 -0.50866215477026122} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c1 -y {-9.8100000000000005 * c1.mass} -gravitational 1
body c2 -shape cube -mass 1 -init_pos {-0.96480048348736824 1 1.0967294311433138} -init_rot {-0.073879164695530131 1.6501553392528887 -1.2404946349540174} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c2 -y {-9.8100000000000005 * c2.mass} -gravitational 1
body c3 -shape cube -mass 1 -init_pos {0.92959477461507667 1 1.0814534719824809} -init_rot {0.73730024740600708 1.830914935812479 -0.17579631492428782} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c3 -y {-9.8100000000000005 * c3.mass} -gravitational 1
body c4 -shape cube -mass 1 -init_pos {-0.98737177221269534 2.7999999999999998 -0.93974692313834973} -init_rot {1.7727104845784698 -1.1065628676523707 0.81175909779025002} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c4 -y {-9.8100000000000005 * c4.mass} -gravitational 1
body c5 -shape cube -mass 1 -init_pos {0.99998901764263648 2.7999999999999998 -1.0594678553067507} -init_rot {0.51745827478931128 -1.4228050799206022 -1.7881938882794921} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c5 -y {-9.8100000000000005 * c5.mass} -gravitational 1
body c6 -shape cube -mass 1 -init_pos {-1.067126394775574 2.7999999999999998 1.0732453138254383} -init_rot {-1.8502852503818947 -1.1294334419276024 1.9462445859094917} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c6 -y {-9.8100000000000005 * c6.mass} -gravitational 1
body c7 -shape cube -mass 1 -init_pos {0.93456843746594687 2.7999999999999998 0.92432075989281182} -init_rot {0.18185441179667539 -0.31310227475441965 0.43303222064982005} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c7 -y {-9.8100000000000005 * c7.mass} -gravitational 1
body c8 -shape cube -mass 1 -init_pos {-0.94211470571343636 4.5999999999999996 -0.91465179310202882} -init_rot {-0.92569689994904758 -0.78306240219380996 0.95025286396895581} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c8 -y {-9.8100000000000005 * c8.mass} -gravitational 1
body c9 -shape cube -mass 1 -init_pos {1.0857832993578189 4.5999999999999996 -1.0958855291612843} -init_rot {1.7446071928122295 0.28300334929070248 -1.3907145475641189} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c9 -y {-9.8100000000000005 * c9.mass} -gravitational 1
body c10 -shape cube -mass 1 -init_pos {-1.0472194588238246 4.5999999999999996 1.0635172745088357} -init_rot {0.90344599973056461 -1.9420055215918386 -0.22720170924424199} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c10 -y {-9.8100000000000005 * c10.mass} -gravitational 1
body c11 -shape cube -mass 1 -init_pos {1.0137451406205469 4.5999999999999996 1.0001393609705855} -init_rot {1.2191581609875395 -0.35911514757539176 -1.8056461317015637} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c11 -y {-9.8100000000000005 * c11.mass} -gravitational 1
body c12 -shape cube -mass 1 -init_pos {-0.98573502299504334 6.4000000000000004 -1.0471825760880711} -init_rot {0.77410983956754364 1.6393546492579554 0.29357262667424777} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c12 -y {-9.8100000000000005 * c12.mass} -gravitational 1
body c13 -shape cube -mass 1 -init_pos {1.0273060287578375 6.4000000000000004 -0.98384644507865626} -init_rot {-0.74487343294411867 0.10535016087325566 0.58295764644237025} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c13 -y {-9.8100000000000005 * c13.mass} -gravitational 1
body c14 -shape cube -mass 1 -init_pos {-1.0533562670180874 6.4000000000000004 0.91222697177174839} -init_rot {0.36737396985296789 0.2079500601519344 1.3920624183570038} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c14 -y {-9.8100000000000005 * c14.mass} -gravitational 1
body c15 -shape cube -mass 1 -init_pos {1.0523079837180944 6.4000000000000004 0.97479821010834866} -init_rot {0.17325841225232219 1.8179644625924074 -1.4824167148533673} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c15 -y {-9.8100000000000005 * c15.mass} -gravitational 1
body c16 -shape cube -mass 1 -init_pos {-1.0964048082643474 8.1999999999999993 -0.98745256867900189} -init_rot {-0.60261473530750931 0.57643534843402655 -0.87285537210297059} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c16 -y {-9.8100000000000005 * c16.mass} -gravitational 1
body c17 -shape cube -mass 1 -init_pos {0.98505127154869632 8.1999999999999993 -1.0241099082110718} -init_rot {-1.4824308442672849 0.41330732807468262 -1.7119815104720586} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c17 -y {-9.8100000000000005 * c17.mass} -gravitational 1
body c18 -shape cube -mass 1 -init_pos {-1.0276260969714532 8.1999999999999993 0.99093760938411379} -init_rot {1.6108281248682697 -0.92210473412909488 -1.6351230734131041} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c18 -y {-9.8100000000000005 * c18.mass} -gravitational 1
body c19 -shape cube -mass 1 -init_pos {1.0391348063015979 8.1999999999999993 1.0377617940260147} -init_rot {-1.8096950893105335 -0.72555428556547552 1.659399817365153} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c19 -y {-9.8100000000000005 * c19.mass} -gravitational 1
body c20 -shape cube -mass 1 -init_pos {-0.92495073827983731 10 -0.99487904745173916} -init_rot {-1.0553131600741232 -1.4724214518446297 0.18824161990758403} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c20 -y {-9.8100000000000005 * c20.mass} -gravitational 1
body c21 -shape cube -mass 1 -init_pos {1.0747425246550644 10 -0.97035440659147065} -init_rot {-0.27707122088276415 -0.36267141886551424 1.1451144360104646} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c21 -y {-9.8100000000000005 * c21.mass} -gravitational 1
body c22 -shape cube -mass 1 -init_pos {-1.0474023565008566 10 0.95610294553464503} -init_rot {-1.9078080459635913 0.68985203672401063 -1.4272761713536317} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c22 -y {-9.8100000000000005 * c22.mass} -gravitational 1
body c23 -shape cube -mass 1 -init_pos {0.91647076679616979 10 1.0342264323733581} -init_rot {0.95345177066869313 0.40383805220804492 -1.787844021678497} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c23 -y {-9.8100000000000005 * c23.mass} -gravitational 1
body c24 -shape cube -mass 1 -init_pos {-1.0429467731066182 11.800000000000001 -0.95038952522899067} -init_rot {-0.34030173086855142 -1.4529685208072811 0.00095679993693309484} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c24 -y {-9.8100000000000005 * c24.mass} -gravitational 1
body c25 -shape cube -mass 1 -init_pos {0.93088642181505799 11.800000000000001 -1.0847364530839778} -init_rot {1.6894024038733964 -1.3128870285208132 0.036275799969704092} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c25 -y {-9.8100000000000005 * c25.mass} -gravitational 1
body c26 -shape cube -mass 1 -init_pos {-1.0609705488356074 11.800000000000001 1.007912309703777} -init_rot {1.2018724692570446 -1.2566864152115547 -0.74654434884199272} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c26 -y {-9.8100000000000005 * c26.mass} -gravitational 1
body c27 -shape cube -mass 1 -init_pos {0.91639796113632632 11.800000000000001 1.0226207841192576} -init_rot {-0.67096404582498703 1.6117739771349715 0.24932474113597358} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c27 -y {-9.8100000000000005 * c27.mass} -gravitational 1
body c28 -shape cube -mass 1 -init_pos {-1.017298894377024 13.6 -1.0505049065279968} -init_rot {1.4094931789792926 0.29371540543613772 0.57173308945894963} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c28 -y {-9.8100000000000005 * c28.mass} -gravitational 1
body c29 -shape cube -mass 1 -init_pos {1.0825691938047195 13.6 -0.97995644786902913} -init_rot {0.37143745230878089 0.56873052325607665 -0.08656916418819649} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c29 -y {-9.8100000000000005 * c29.mass} -gravitational 1
simulator -finish 5
