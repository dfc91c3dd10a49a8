"""The size effect of the beams of scripts/gregoire2013.py (Bažant's law
fitted per notch, the unnotched slope, the uniform-G_f beams beside them):
size_effect.md|csv|png and cracks.png in the folder. The same as
`scripts/gregoire2013.py size-effect --out FOLDER`; the tables are
ldem.study.beam_tables.

    /usr/bin/python3 scripts/beam_size_effect.py results/beams/gregoire2013
"""
import sys

import gregoire2013

if __name__ == "__main__":
    gregoire2013.main(["size-effect", "--out", sys.argv[1] if len(sys.argv) > 1 else gregoire2013.OUT])
