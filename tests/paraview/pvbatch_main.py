"""What the ParaView test scripts share, written once: their required options and how the pvbatch
scripts end."""
import argparse
import sys


def required_options(*names):
    """The parsed command line of a script whose options are all required strings: --name for each
    of `names`, read back as args.name (dashes as underscores)."""
    p = argparse.ArgumentParser()
    for name in names:
        p.add_argument("--" + name, required=True)
    return p.parse_args()


def run(main):
    """Runs main() and exits with its status when it failed. On success it returns and the script
    falls off the end: sys.exit after rendering makes pvbatch tear the OpenGL context down after
    the X display and fail with GLXBadContext."""
    status = main()
    if status:
        sys.stdout.flush()  # pvbatch's exit does not flush what the failed checks printed
        sys.exit(status)


FAILURES = []


def check(condition, message):
    """Records a failed check (printed as it happens); status() tells the outcome."""
    print(("ok: " if condition else "FAIL: ") + message)
    if not condition:
        FAILURES.append(message)


def status():
    """main()'s return value after its check() calls: 0 when all passed, else 1."""
    if FAILURES:
        print("%d check(s) failed" % len(FAILURES))
        return 1
    print("all checks passed")
    return 0
