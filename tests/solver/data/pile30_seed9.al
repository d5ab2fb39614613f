shape_set cube -desc {-sub {-box {1 1 1}}}
shape_set ball -desc {-sub {-sphere 0.2}}
shape_set floor -desc {-sub {-box {60 1 60}}}
body floor -shape floor -static 1 -init_pos {0 -0.5 0} -restitution 0.5 -friction 0.5
body c0 -shape cube -mass 1 -init_pos {-1.0271077947686251 1 -1.0001739268423115} -init_rot {-1.96982759936175 -0.73510275209897236 -1.9467119563910076} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c0 -y {-9.8100000000000005 * c0.mass} -gravitational 1
body c1 -shape cube -mass 1 -init_pos {1.0754442418095915 1 -1.0724946360840226} -init_rot {-1.4455468792020332 -0.41645659032830995 -0.021381943164860306} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c1 -y {-9.8100000000000005 * c1.mass} -gravitational 1
body c2 -shape cube -mass 1 -init_pos {-1.0368582265373889 1 0.97479023620852079} -init_rot {0.93863218645654989 1.8716163132700587 0.80619379663756785} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c2 -y {-9.8100000000000005 * c2.mass} -gravitational 1
body c3 -shape cube -mass 1 -init_pos {0.92708502908110435 1 0.92720139589617068} -init_rot {1.8032286340993822 0.2122227480149248 1.7732276252493517} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c3 -y {-9.8100000000000005 * c3.mass} -gravitational 1
body c4 -shape cube -mass 1 -init_pos {-0.97408979482080427 2.7999999999999998 -0.98702605871043925} -init_rot {0.55827295018813627 1.0600735698506876 -0.49916262743945761} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c4 -y {-9.8100000000000005 * c4.mass} -gravitational 1
body c5 -shape cube -mass 1 -init_pos {1.0668591667340948 2.7999999999999998 -1.0791084082804918} -init_rot {-1.6827360082700511 -1.7293217503269345 -0.036081318794267903} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c5 -y {-9.8100000000000005 * c5.mass} -gravitational 1
body c6 -shape cube -mass 1 -init_pos {-1.058106634037125 2.7999999999999998 1.0850446903547659} -init_rot {1.9224422024291439 0.67852244077766466 0.32700555980495727} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c6 -y {-9.8100000000000005 * c6.mass} -gravitational 1
body c7 -shape cube -mass 1 -init_pos {1.0588634883460311 2.7999999999999998 0.90934000690031225} -init_rot {0.32104085363287282 -1.7019548524665629 -1.359719854347841} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c7 -y {-9.8100000000000005 * c7.mass} -gravitational 1
body c8 -shape cube -mass 1 -init_pos {-1.0130222540064464 4.5999999999999996 -0.98124716302862947} -init_rot {-1.4393673534710203 1.5956919513973924 1.9148780963108019} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c8 -y {-9.8100000000000005 * c8.mass} -gravitational 1
body c9 -shape cube -mass 1 -init_pos {1.0859475785487964 4.5999999999999996 -1.0214437749382261} -init_rot {-0.84264220045550808 -0.73299004051350058 1.9475775193790485} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c9 -y {-9.8100000000000005 * c9.mass} -gravitational 1
body c10 -shape cube -mass 1 -init_pos {-1.0914296655614339 4.5999999999999996 0.93402282831436279} -init_rot {-0.88108867643242927 -0.38633189811086344 0.69485727887467563} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c10 -y {-9.8100000000000005 * c10.mass} -gravitational 1
body c11 -shape cube -mass 1 -init_pos {0.94792163302980048 4.5999999999999996 0.93549207080130226} -init_rot {-1.4865749178802539 -1.7196577637095576 0.54229132305171035} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c11 -y {-9.8100000000000005 * c11.mass} -gravitational 1
body c12 -shape cube -mass 1 -init_pos {-0.92597619963416367 6.4000000000000004 -1.0291507149255956} -init_rot {-1.860871367341693 1.1168450417618958 -0.093220318751897402} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c12 -y {-9.8100000000000005 * c12.mass} -gravitational 1
body c13 -shape cube -mass 1 -init_pos {0.91424393951999339 6.4000000000000004 -0.91934672117349114} -init_rot {1.2169681407507817 -1.9817446159731549 -1.129289645288035} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c13 -y {-9.8100000000000005 * c13.mass} -gravitational 1
body c14 -shape cube -mass 1 -init_pos {-0.95408698532273339 6.4000000000000004 0.96395105572484185} -init_rot {0.19547455870942754 -1.852911514028311 1.2689278099986789} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c14 -y {-9.8100000000000005 * c14.mass} -gravitational 1
body c15 -shape cube -mass 1 -init_pos {1.0035894080404697 6.4000000000000004 1.0039027928568385} -init_rot {1.3454069007038121 -1.96741982410258 -0.65174570080819838} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c15 -y {-9.8100000000000005 * c15.mass} -gravitational 1
body c16 -shape cube -mass 1 -init_pos {-0.98506832319615567 8.1999999999999993 -1.0730144511183624} -init_rot {-1.4128470818487642 -1.7825461719457076 0.2271005988352397} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c16 -y {-9.8100000000000005 * c16.mass} -gravitational 1
body c17 -shape cube -mass 1 -init_pos {1.0925863160350717 8.1999999999999993 -0.95669340199721353} -init_rot {0.27299434551217505 1.151697598568306 1.9676621911202656} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c17 -y {-9.8100000000000005 * c17.mass} -gravitational 1
body c18 -shape cube -mass 1 -init_pos {-1.0920741341291194 8.1999999999999993 0.95628752309313503} -init_rot {0.79992358116717455 -1.4030431662773699 1.2499296997041363} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c18 -y {-9.8100000000000005 * c18.mass} -gravitational 1
body c19 -shape cube -mass 1 -init_pos {0.90597482780171412 8.1999999999999993 1.067299536964861} -init_rot {-0.58217057205406619 0.36944321616675557 -1.9708569713327697} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c19 -y {-9.8100000000000005 * c19.mass} -gravitational 1
body c20 -shape cube -mass 1 -init_pos {-0.93771709118679758 10 -0.91212584031276134} -init_rot {-1.3639000571172752 1.9221725077530931 1.6011983092255329} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c20 -y {-9.8100000000000005 * c20.mass} -gravitational 1
body c21 -shape cube -mass 1 -init_pos {0.91378884404490435 10 -0.95371035105354895} -init_rot {-0.17875290238664054 1.0415372115196813 0.90482263413800457} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c21 -y {-9.8100000000000005 * c21.mass} -gravitational 1
body c22 -shape cube -mass 1 -init_pos {-0.938277969029087 10 0.97279876814184818} -init_rot {1.6877316865074361 0.17845852949205598 -1.83331989262224} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c22 -y {-9.8100000000000005 * c22.mass} -gravitational 1
body c23 -shape cube -mass 1 -init_pos {1.0765157089523516 10 1.013616260618428} -init_rot {-1.9432173869372464 0.28165484546287534 1.3797735458361648} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c23 -y {-9.8100000000000005 * c23.mass} -gravitational 1
body c24 -shape cube -mass 1 -init_pos {-1.08473372324029 11.800000000000001 -0.94446919123473538} -init_rot {1.0287318199912416 1.2478845356091122 0.93026036586281968} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c24 -y {-9.8100000000000005 * c24.mass} -gravitational 1
body c25 -shape cube -mass 1 -init_pos {0.90676874889839687 11.800000000000001 -0.94162988682841287} -init_rot {0.30190591506560249 -0.065407057702368432 -1.5323511381002897} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c25 -y {-9.8100000000000005 * c25.mass} -gravitational 1
body c26 -shape cube -mass 1 -init_pos {-0.90957348787652403 11.800000000000001 0.95879991456581704} -init_rot {-1.324254872528015 -0.95169175723440014 -0.7994485891188039} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c26 -y {-9.8100000000000005 * c26.mass} -gravitational 1
body c27 -shape cube -mass 1 -init_pos {0.9141485763198669 11.800000000000001 0.95664509235493134} -init_rot {1.8452474164610289 1.915077286626321 -0.92936993702769377} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c27 -y {-9.8100000000000005 * c27.mass} -gravitational 1
body c28 -shape cube -mass 1 -init_pos {-1.0934463695947687 13.6 -0.90499072480812759} -init_rot {0.74522906564615621 0.49486525049785213 -1.4082008166835753} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c28 -y {-9.8100000000000005 * c28.mass} -gravitational 1
body c29 -shape cube -mass 1 -init_pos {0.98143976341843653 13.6 -1.0125855005263062} -init_rot {-0.6496020333042074 -1.1798764298854083 -0.17172216642313765} -init_dpos {0 0 0} -restitution 0.5 -friction 0.5
force -body c29 -y {-9.8100000000000005 * c29.mass} -gravitational 1
simulator -finish 5
