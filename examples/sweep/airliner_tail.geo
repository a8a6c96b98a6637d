// airliner.geo without its nacelles and pylons, 10 long (written for Strata's sweep, 2026-12-05,
// issue 54): the fuselage, the swept wing with rounded leading edges and sharp trailing edges
// ending on the fuselage, the tailplane and the fin; nothing narrow between the parts (--fuse).
nacelles = 0;
Include "airliner.geo";
