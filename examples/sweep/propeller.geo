SetFactory("OpenCASCADE");
// A three-bladed propeller, 2 across (written for Strata's sweep, 2026-11-27): a spinner (a
// cylinder with a stretched-sphere nose) and three twisted blades lofted through NACA 00xx
// sections with sharp trailing edges, fused (--fuse). The blades' roots sink into the spinner;
// their tips are flat. The sections' pitch falls from 50 to 15 degrees along the span.

// A NACA 00t section with a sharp trailing edge as a wire of two splines (upper and lower),
// chord c, in the plane y = r, its leading edge at x = x0 before it is turned by the pitch
// angle pitch about the y axis, then by phi about the z axis.
Macro BladeSection
  n = 30;
  For i In {0:n}
    xs[i] = 0.5 * (1 - Cos(Pi * i / n));
  EndFor
  For i In {0:2 * n - 1}
    If (i <= n)
      x = xs[n - i]; sign = 1;
    Else
      x = xs[i - n]; sign = -1;
    EndIf
    yt = 5 * t * (0.2969 * Sqrt(x) - 0.1260 * x - 0.3516 * x^2 + 0.2843 * x^3 - 0.1036 * x^4);
    X = x0 + c * x; Z = sign * c * yt;
    Xp = X * Cos(pitch) + Z * Sin(pitch); Zp = -X * Sin(pitch) + Z * Cos(pitch);
    pts[i] = newp; Point(pts[i]) = {Xp * Cos(phi) - r * Sin(phi), Xp * Sin(phi) + r * Cos(phi), Zp};
  EndFor
  s1 = newc; Spline(s1) = {pts[{0:n}]};
  s2 = newc; Spline(s2) = {pts[{n:2 * n - 1}], pts[0]};
  sec = newll; Wire(sec) = {s1, s2};
Return

Cylinder(1) = {0, 0, -0.3, 0, 0, 0.6, 0.15};
Sphere(2) = {0, 0, -0.3, 0.15};
Dilate {{0, 0, -0.3}, {1, 1, 2}} { Volume{2}; }
For b In {0:2}
  phi = b * 2 * Pi / 3;
  For j In {0:3}
    r = 0.1 + 0.9 * j / 3;
    c = 0.22 - 0.12 * j / 3;
    t = 0.16 - 0.06 * j / 3;
    pitch = (50 - 35 * j / 3) * Pi / 180;
    x0 = -0.3 * c;
    Call BladeSection;
    blade[j] = sec;
  EndFor
  ThruSections(10 + b) = {blade[0], blade[1], blade[2], blade[3]};
EndFor
