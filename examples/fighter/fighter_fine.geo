// The notional fighter of fighter.geo (see there: what it is, its dimensions, where it comes
// from) with a finer surface mesh: h = 0.13 on the aircraft instead of 0.265 (and h/3 along
// the leading edges, h/4 on the inlet lip), 14,540 triangles on the aircraft instead of
// 4,486 (3.2 times as many).
h = 0.13;
Include "fighter.geo";
