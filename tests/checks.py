"""The one reporting helper of the test scripts (tests/check_*.py and the script-style
tests/test_*.py). They run as `python3 tests/<script>.py ...`, which puts this directory first
on sys.path, so `from checks import Checks` finds this file.

    check = Checks()                   # marks 'ok      ' / 'FAILED  '
    check(x <= 1, f'x {x:g} <= 1')     # prints the mark and the message, returns bool(condition)
    sys.exit(check.exit_code())        # 0 if every check passed, else 1

Checks(passed='ok    ', failed='FAIL  ') gives the narrower marks some scripts print.
check.passed counts the checks that passed, check.failures lists the messages of those that
failed (check.failed is their number) and check.ok says whether none did."""

WIDE = ('ok      ', 'FAILED  ')
NARROW = ('ok    ', 'FAIL  ')


class Checks:
    """A callable check(condition, message) that prints one line per check and counts them."""

    def __init__(self, passed=WIDE[0], failed=WIDE[1]):
        self.marks = (passed, failed)
        self.passed = 0
        self.failures = []

    def __call__(self, condition, message):
        good = bool(condition)
        print((self.marks[0] if good else self.marks[1]) + message)
        if good:
            self.passed += 1
        else:
            self.failures.append(message)
        return good

    @property
    def failed(self):
        return len(self.failures)

    @property
    def ok(self):
        return not self.failures

    def exit_code(self):
        return 0 if self.ok else 1
