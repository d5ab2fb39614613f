shape_set cube -desc {-sub {-box {1 1 1}}}
shape_set ball -desc {-sub {-sphere 0.2}}
shape_set floor -desc {-sub {-box {60 1 60}}}
body floor -shape floor -static 1 -init_pos {0 -0.5 0} -restitution 0.5 -friction 0.5
body c0 -shape cube -mass 1 -init_pos {-0.97853173386409398 1 -0.92811319752421506} -init_rot {1.5719307389336437 -1.283386087076972 1.0343360258011156} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c0 -y {-9.8100000000000005 * c0.mass} -gravitational 1
body c1 -shape cube -mass 1 -init_pos {1.050332303086922 1 -0.97853133088866984} -init_rot {1.1760853964607478 -0.4478280789762612 -0.63861124709060579} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c1 -y {-9.8100000000000005 * c1.mass} -gravitational 1
body c2 -shape cube -mass 1 -init_pos {-0.96761756785982111 1 1.08110955964301} -init_rot {0.88012208329375152 -0.11363087235292335 -0.011978665019521495} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c2 -y {-9.8100000000000005 * c2.mass} -gravitational 1
body c3 -shape cube -mass 1 -init_pos {0.98925323838739876 1 1.0061150857366752} -init_rot {1.9729866053420877 0.45781639964265075 -1.2787730150312802} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c3 -y {-9.8100000000000005 * c3.mass} -gravitational 1
body c4 -shape cube -mass 1 -init_pos {-0.9554262741026891 2.7999999999999998 -0.91217868974349003} -init_rot {0.15355250548514654 -0.11944854919074821 0.4977301303594408} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c4 -y {-9.8100000000000005 * c4.mass} -gravitational 1
body c5 -shape cube -mass 1 -init_pos {1.0379556278262791 2.7999999999999998 -1.0422467935537068} -init_rot {-1.7886537445021669 1.1506808465427865 0.10337542532624422} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c5 -y {-9.8100000000000005 * c5.mass} -gravitational 1
body c6 -shape cube -mass 1 -init_pos {-1.0606336774391663 2.7999999999999998 1.0190407875029239} -init_rot {0.17233394426894888 -0.19403509841369271 0.046316301897059375} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c6 -y {-9.8100000000000005 * c6.mass} -gravitational 1
body c7 -shape cube -mass 1 -init_pos {1.0336380891946877 2.7999999999999998 0.92367120431736172} -init_rot {-1.5538945251638268 1.3465941163825175 -0.91217786229720144} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c7 -y {-9.8100000000000005 * c7.mass} -gravitational 1
body c8 -shape cube -mass 1 -init_pos {-0.97637735762274847 4.5999999999999996 -0.98206816885175907} -init_rot {0.746309837250553 -0.799124515387718 0.49564150856629574} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c8 -y {-9.8100000000000005 * c8.mass} -gravitational 1
body c9 -shape cube -mass 1 -init_pos {0.91778544649728544 4.5999999999999996 -0.99247622110977152} -init_rot {-1.7330815236973214 -0.88086994944850106 -1.555225566897618} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c9 -y {-9.8100000000000005 * c9.mass} -gravitational 1
body c10 -shape cube -mass 1 -init_pos {-0.99135573824466738 4.5999999999999996 1.0251052790111053} -init_rot {-0.012394294014213658 0.85748047297704355 -1.1744480242528401} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c10 -y {-9.8100000000000005 * c10.mass} -gravitational 1
body c11 -shape cube -mass 1 -init_pos {1.0985581065133114 4.5999999999999996 0.93554392978204393} -init_rot {1.9834384654463317 0.1344823550783647 -1.6366090238384108} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c11 -y {-9.8100000000000005 * c11.mass} -gravitational 1
body c12 -shape cube -mass 1 -init_pos {-1.0448990649750163 6.4000000000000004 -1.0628091915011062} -init_rot {-0.19876249056336603 -0.30377680398028395 -1.9883573668591017} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c12 -y {-9.8100000000000005 * c12.mass} -gravitational 1
body c13 -shape cube -mass 1 -init_pos {1.0007713837172334 6.4000000000000004 -1.0075011023557447} -init_rot {1.1696944168880807 -1.9501863308391176 0.99178292776903731} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c13 -y {-9.8100000000000005 * c13.mass} -gravitational 1
body c14 -shape cube -mass 1 -init_pos {-0.9019055647543146 6.4000000000000004 0.93793785092918114} -init_rot {-1.461390328674379 -1.2756238557725066 -1.8808600956326464} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c14 -y {-9.8100000000000005 * c14.mass} -gravitational 1
body c15 -shape cube -mass 1 -init_pos {0.9797624339755826 6.4000000000000004 0.93338994566054823} -init_rot {-1.8400492759082652 1.8564435938330361 -0.56649074278406553} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c15 -y {-9.8100000000000005 * c15.mass} -gravitational 1
body c16 -shape cube -mass 1 -init_pos {-1.0945825825464477 8.1999999999999993 -0.99089869966482558} -init_rot {1.1087450637751801 0.26382989879750429 -0.20320840161141551} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c16 -y {-9.8100000000000005 * c16.mass} -gravitational 1
body c17 -shape cube -mass 1 -init_pos {1.0964448036707812 8.1999999999999993 -0.99482657497575888} -init_rot {1.5427573782766806 0.52774791230191775 -1.554213115812255} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c17 -y {-9.8100000000000005 * c17.mass} -gravitational 1
body c18 -shape cube -mass 1 -init_pos {-1.012749873295214 8.1999999999999993 0.94349090902457977} -init_rot {-0.31325817004842227 0.52274484940641885 -0.48602579630309517} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c18 -y {-9.8100000000000005 * c18.mass} -gravitational 1
body c19 -shape cube -mass 1 -init_pos {0.90428066669005425 8.1999999999999993 1.0957451877222351} -init_rot {1.033742515621134 -1.875256599252922 0.36903569060077634} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c19 -y {-9.8100000000000005 * c19.mass} -gravitational 1
body c20 -shape cube -mass 1 -init_pos {-0.98337237794433141 10 -0.93390908953905583} -init_rot {0.94894290182527286 1.6396512372732408 1.1411321515642778} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c20 -y {-9.8100000000000005 * c20.mass} -gravitational 1
body c21 -shape cube -mass 1 -init_pos {0.97930497374498349 10 -1.033669061554181} -init_rot {-0.25831206314871591 -0.96065347902141696 1.6591433641199012} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c21 -y {-9.8100000000000005 * c21.mass} -gravitational 1
body c22 -shape cube -mass 1 -init_pos {-1.0580435429350712 10 0.96252393015567583} -init_rot {-1.162355703186001 0.16764935872033915 -0.56555019106766258} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c22 -y {-9.8100000000000005 * c22.mass} -gravitational 1
body c23 -shape cube -mass 1 -init_pos {1.0795448911392047 10 1.024261013244018} -init_rot {-1.768117024871656 -0.14094096723951477 -1.2875356001537159} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c23 -y {-9.8100000000000005 * c23.mass} -gravitational 1
body c24 -shape cube -mass 1 -init_pos {-0.9485985628975625 11.800000000000001 -0.90171570326610206} -init_rot {1.9535839301921527 -0.7213059287760919 1.8859981559339918} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c24 -y {-9.8100000000000005 * c24.mass} -gravitational 1
body c25 -shape cube -mass 1 -init_pos {1.049769967646772 11.800000000000001 -1.0956149035218841} -init_rot {-1.6754708727079257 -0.36818901340321153 1.3204056172055649} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c25 -y {-9.8100000000000005 * c25.mass} -gravitational 1
body c26 -shape cube -mass 1 -init_pos {-0.9286642567457557 11.800000000000001 0.90086823084157808} -init_rot {-1.0890833911066848 0.13697139089789134 -1.0631922040505508} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c26 -y {-9.8100000000000005 * c26.mass} -gravitational 1
body c27 -shape cube -mass 1 -init_pos {0.99891244032001425 11.800000000000001 1.0240190222836505} -init_rot {-1.0985987850017369 -1.8215003829707894 0.78781033191688099} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c27 -y {-9.8100000000000005 * c27.mass} -gravitational 1
body c28 -shape cube -mass 1 -init_pos {-1.0272631783005282 13.6 -0.98241558565656439} -init_rot {0.91184371311284051 1.4770752145366823 1.4317346442446501} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c28 -y {-9.8100000000000005 * c28.mass} -gravitational 1
body c29 -shape cube -mass 1 -init_pos {0.96446978757909219 13.6 -1.0190135467668957} -init_rot {-0.24184114744281082 1.5346338341987544 1.567785592876592} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c29 -y {-9.8100000000000005 * c29.mass} -gravitational 1
simulator -finish 5
