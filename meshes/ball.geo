// All-hex ball of diameter D: a cube core and six shell blocks (a cubed sphere), meshed
// by transfinite interpolation and recombined into hexahedra.
// Parameters (override with gmsh -setnumber NAME VALUE):
//   D  ball diameter, m;  h  target element size, m;  core  core half-width / radius.
// Physical groups: volume "ball", surface "surface" (the sphere).
If (!Exists(D))
  D = 0.02;
EndIf
If (!Exists(h))
  h = 0.002;
EndIf
If (!Exists(core))
  core = 0.55;
EndIf
R = D / 2;
a = core * R / Sqrt(3);  // core corner at radius core * R
s = R / Sqrt(3);         // sphere corner
// Cells along a core edge: the arc between two sphere corners is R acos(1/3) long.
N = Ceil(R * Acos(1 / 3) / h);
M = Ceil((R - core * R) / h);
Point(1) = {0, 0, 0, h};
Point(10) = {-1 * a, -1 * a, -1 * a, h};
Point(11) = {-1 * a, -1 * a, 1 * a, h};
Point(12) = {-1 * a, 1 * a, -1 * a, h};
Point(13) = {-1 * a, 1 * a, 1 * a, h};
Point(14) = {1 * a, -1 * a, -1 * a, h};
Point(15) = {1 * a, -1 * a, 1 * a, h};
Point(16) = {1 * a, 1 * a, -1 * a, h};
Point(17) = {1 * a, 1 * a, 1 * a, h};
Point(20) = {-1 * s, -1 * s, -1 * s, h};
Point(21) = {-1 * s, -1 * s, 1 * s, h};
Point(22) = {-1 * s, 1 * s, -1 * s, h};
Point(23) = {-1 * s, 1 * s, 1 * s, h};
Point(24) = {1 * s, -1 * s, -1 * s, h};
Point(25) = {1 * s, -1 * s, 1 * s, h};
Point(26) = {1 * s, 1 * s, -1 * s, h};
Point(27) = {1 * s, 1 * s, 1 * s, h};
Line(100) = {10, 11};
Circle(200) = {20, 1, 21};
Line(101) = {10, 12};
Circle(201) = {20, 1, 22};
Line(102) = {10, 14};
Circle(202) = {20, 1, 24};
Line(103) = {11, 13};
Circle(203) = {21, 1, 23};
Line(104) = {11, 15};
Circle(204) = {21, 1, 25};
Line(105) = {12, 13};
Circle(205) = {22, 1, 23};
Line(106) = {12, 16};
Circle(206) = {22, 1, 26};
Line(107) = {13, 17};
Circle(207) = {23, 1, 27};
Line(108) = {14, 15};
Circle(208) = {24, 1, 25};
Line(109) = {14, 16};
Circle(209) = {24, 1, 26};
Line(110) = {15, 17};
Circle(210) = {25, 1, 27};
Line(111) = {16, 17};
Circle(211) = {26, 1, 27};
Line(300) = {10, 20};
Line(301) = {11, 21};
Line(302) = {12, 22};
Line(303) = {13, 23};
Line(304) = {14, 24};
Line(305) = {15, 25};
Line(306) = {16, 26};
Line(307) = {17, 27};
Curve Loop(400) = {101, 105, -103, -100};
Plane Surface(400) = {400};
Curve Loop(410) = {201, 205, -203, -200};
Surface(410) = {410} In Sphere {1};
Curve Loop(401) = {109, 111, -110, -108};
Plane Surface(401) = {401};
Curve Loop(411) = {209, 211, -210, -208};
Surface(411) = {411} In Sphere {1};
Curve Loop(402) = {102, 108, -104, -100};
Plane Surface(402) = {402};
Curve Loop(412) = {202, 208, -204, -200};
Surface(412) = {412} In Sphere {1};
Curve Loop(403) = {106, 111, -107, -105};
Plane Surface(403) = {403};
Curve Loop(413) = {206, 211, -207, -205};
Surface(413) = {413} In Sphere {1};
Curve Loop(404) = {102, 109, -106, -101};
Plane Surface(404) = {404};
Curve Loop(414) = {202, 209, -206, -201};
Surface(414) = {414} In Sphere {1};
Curve Loop(405) = {104, 110, -107, -103};
Plane Surface(405) = {405};
Curve Loop(415) = {204, 210, -207, -203};
Surface(415) = {415} In Sphere {1};
Curve Loop(500) = {100, 301, -200, -300};
Surface(500) = {500};
Curve Loop(501) = {101, 302, -201, -300};
Surface(501) = {501};
Curve Loop(502) = {102, 304, -202, -300};
Surface(502) = {502};
Curve Loop(503) = {103, 303, -203, -301};
Surface(503) = {503};
Curve Loop(504) = {104, 305, -204, -301};
Surface(504) = {504};
Curve Loop(505) = {105, 303, -205, -302};
Surface(505) = {505};
Curve Loop(506) = {106, 306, -206, -302};
Surface(506) = {506};
Curve Loop(507) = {107, 307, -207, -303};
Surface(507) = {507};
Curve Loop(508) = {108, 305, -208, -304};
Surface(508) = {508};
Curve Loop(509) = {109, 306, -209, -304};
Surface(509) = {509};
Curve Loop(510) = {110, 307, -210, -305};
Surface(510) = {510};
Curve Loop(511) = {111, 307, -211, -306};
Surface(511) = {511};
Surface Loop(600) = {400, 401, 402, 403, 404, 405};
Volume(600) = {600};
Surface Loop(610) = {400, 410, 501, 505, 503, 500};
Volume(610) = {610};
Surface Loop(611) = {401, 411, 509, 511, 510, 508};
Volume(611) = {611};
Surface Loop(612) = {402, 412, 502, 508, 504, 500};
Volume(612) = {612};
Surface Loop(613) = {403, 413, 506, 511, 507, 505};
Volume(613) = {613};
Surface Loop(614) = {404, 414, 502, 509, 506, 501};
Volume(614) = {614};
Surface Loop(615) = {405, 415, 504, 510, 507, 503};
Volume(615) = {615};
Transfinite Curve{100:111, 200:211} = N + 1;
Transfinite Curve{300:307} = M + 1;
Transfinite Surface{:};
Recombine Surface{:};
Transfinite Volume{:};
Physical Volume("ball", 1) = {600, 610:615};
Physical Surface("surface", 2) = {410:415};
Mesh.RecombineAll = 1;
