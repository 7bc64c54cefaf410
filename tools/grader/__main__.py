"""`python3 tools/grader ...`: runs the grader's command line (cli.py)."""

import sys
from pathlib import Path

# Run as a folder, Python puts the folder itself first on the path: put tools/ there instead, so
# the modules are the package's (grader.*) and tools/course.py is found beside it
sys.path[0] = str(Path(__file__).resolve().parent.parent)

from grader.cli import main  # noqa: E402

sys.exit(main())
