"""Paths of the add-on's SVG icons."""
import os

ICON_DIR = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
                        "Resources", "icons")


def path(name):
    return os.path.join(ICON_DIR, name)
