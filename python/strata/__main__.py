"""python3 -m strata: the keywords of strata.mesh() with their defaults and C++ parameters."""

from . import keywords

for k in keywords():
    print(f"{k['name']:20s} {k['default']!r:12s} {k['param'] or '(front-end switch)':40s} {','.join(k['takes'])}")
