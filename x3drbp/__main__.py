"""`python -m x3drbp`: how the runner starts each child run."""

import sys

from x3drbp import main

sys.exit(main())
