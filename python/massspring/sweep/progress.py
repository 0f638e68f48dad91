"""The sweep's progress bar on stderr: redrawn in place on a terminal, a line at most every
`interval` seconds (and at the end) otherwise, so that a log stays short."""

import sys
import time


class Progress:
    def __init__(self, total, skipped=0, stream=None, interval=10.0, enabled=True):
        self.total, self.skipped = total, skipped
        self.done, self.failed = 0, 0
        self.stream = stream or sys.stderr
        self.interval = interval
        self.enabled = enabled
        self.tty = enabled and hasattr(self.stream, "isatty") and self.stream.isatty()
        self.start = time.monotonic()
        self.printed = -interval

    def advance(self, ok=True):
        self.done += 1
        self.failed += 0 if ok else 1
        self.draw(final=self.done == self.total)

    def line(self):
        elapsed = time.monotonic() - self.start
        width = 30
        filled = int(width * self.done / self.total) if self.total else width
        bar = "#" * filled + "-" * (width - filled)
        left = ""
        if 0 < self.done < self.total:
            left = f", ~{elapsed * (self.total - self.done) / self.done:.0f} s left"
        failed = f", {self.failed} not ok" if self.failed else ""
        return (f"[{bar}] {self.done}/{self.total} runs{failed}, {elapsed:.0f} s{left}")

    def draw(self, final=False):
        if not self.enabled:
            return
        now = time.monotonic() - self.start
        if self.tty:
            self.stream.write("\r" + self.line() + ("\n" if final else ""))
        elif final or now - self.printed >= self.interval:
            self.stream.write(self.line() + "\n")
            self.printed = now
        self.stream.flush()
