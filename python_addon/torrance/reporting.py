# SPDX-License-Identifier: Apache-2.0
"""Messages to the artist: warnings and notes from the export, the render and the panels."""


class Reporter:
    """Collects messages for engine.report(); each distinct message is reported once."""

    def __init__(self, engine=None):
        self.engine = engine
        self.seen = set()
        self.messages = []          # (level, text), in order

    def report(self, level, text):
        if (level, text) in self.seen:
            return
        self.seen.add((level, text))
        self.messages.append((level, text))
        if self.engine is not None:
            try:
                self.engine.report({level}, text)
            except Exception:        # never let reporting break a render
                print(f"Torrance {level}: {text}")
        else:
            print(f"Torrance {level}: {text}")

    def info(self, text):
        self.report('INFO', text)

    def warning(self, text):
        self.report('WARNING', text)

    def error(self, text):
        self.report('ERROR', text)
