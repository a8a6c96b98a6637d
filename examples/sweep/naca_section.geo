// A NACA 00t section with a sharp trailing edge as a wire `sec` of two splines (upper and
// lower), chord c, leading edge at (x0, y0, z0); vertical = 1 puts its thickness along y (a fin).
// Shared by the sweep's scripts (written for Strata's sweep): each `Include "naca_section.geo";`
// builds one section from the variables set before it.
n = 30;
For i In {0:n}
  xs[i] = 0.5 * (1 - Cos(Pi * i / n));
EndFor
For i In {0:n}
  x = xs[n - i];
  yt = 5 * t * (0.2969 * Sqrt(x) - 0.1260 * x - 0.3516 * x^2 + 0.2843 * x^3 - 0.1036 * x^4);
  If (vertical == 0)
    up[i] = newp; Point(up[i]) = {x0 + c * x, y0, z0 + c * yt};
  Else
    up[i] = newp; Point(up[i]) = {x0 + c * x, y0 + c * yt, z0};
  EndIf
EndFor
lo[0] = up[n];
For i In {1:n - 1}
  x = xs[i];
  yt = 5 * t * (0.2969 * Sqrt(x) - 0.1260 * x - 0.3516 * x^2 + 0.2843 * x^3 - 0.1036 * x^4);
  If (vertical == 0)
    lo[i] = newp; Point(lo[i]) = {x0 + c * x, y0, z0 - c * yt};
  Else
    lo[i] = newp; Point(lo[i]) = {x0 + c * x, y0 - c * yt, z0};
  EndIf
EndFor
lo[n] = up[0];
s1 = newc; Spline(s1) = {up[{0:n}]};
s2 = newc; Spline(s2) = {lo[{0:n}]};
sec = newll; Wire(sec) = {s1, s2};
