// Meridian section of a ball of diameter D (the half-disc x = r >= 0, y = z, centred at the
// origin), meshed with quadrangles graded toward the contact pole (0, R).
// Parameters (override with gmsh -setnumber NAME VALUE):
//   D  ball diameter, m;  h  far-field element size, m;  hp  element size at the pole, m;
//   contact  half-angle of the contact arc around the pole, degrees.
// Physical groups: surface "ball"; curves "contact" (the arc within `contact` of the pole),
// "surface" (the whole arc) and "axis" (the segment r = 0).
If (!Exists(D))
  D = 0.02;
EndIf
If (!Exists(h))
  h = 0.002;
EndIf
If (!Exists(hp))
  hp = 0.0002;
EndIf
If (!Exists(contact))
  contact = 30;
EndIf
R = D / 2;
c = contact * Pi / 180;
// gmsh halves every edge in its final all-quad subdivision: ask for twice the sizes.
Point(1) = {0, 0, 0, 2 * h};
Point(2) = {0, -R, 0, 2 * h};
Point(3) = {R * Sin(c), R * Cos(c), 0, 2 * h};
Point(4) = {0, R, 0, 2 * hp};
Circle(1) = {2, 1, 3};
Circle(2) = {3, 1, 4};
Line(3) = {4, 1};
Line(4) = {1, 2};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Surface("ball") = {1};
Physical Curve("contact") = {2};
Physical Curve("surface") = {1, 2};
Physical Curve("axis") = {3, 4};
// Size grows away from the pole: 2 hp there, up to 2 h at a distance of about 10 (h - hp)/1.
Field[1] = Distance;
Field[1].PointsList = {4};
Field[2] = MathEval;
Field[2].F = Sprintf("Min(%g, %g + 0.2 * F1)", 2 * h, 2 * hp);
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Mesh.Algorithm = 6;
Mesh.RecombineAll = 1;
Mesh.RecombinationAlgorithm = 1;
Mesh.SubdivisionAlgorithm = 1;
