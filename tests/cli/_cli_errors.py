"""The bad-input contract of an in-process ``main(...)`` call, for the CLI tests."""


def error_line(capsys, rc):
    """Exit status 2 and exactly one ``error:`` line on stderr, no traceback; the line."""
    cap = capsys.readouterr()
    assert rc == 2
    lines = cap.err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error:"), cap.err
    assert "Traceback" not in cap.err
    return lines[0]
