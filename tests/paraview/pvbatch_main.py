"""How the pvbatch test scripts end, written once."""
import sys


def run(main):
    """Runs main() and exits with its status when it failed. On success it returns and the script
    falls off the end: sys.exit after rendering makes pvbatch tear the OpenGL context down after
    the X display and fail with GLXBadContext."""
    status = main()
    if status:
        sys.exit(status)
