"""``python -m tilekit``: the command line."""

from tilekit.cli import main

if __name__ == "__main__":
    main()
