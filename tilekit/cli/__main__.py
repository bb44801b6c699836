"""``python -m tilekit.cli``: the command line, as before the package split."""

from tilekit.cli import main

if __name__ == "__main__":
    main()
