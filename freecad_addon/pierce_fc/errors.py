"""Errors shown to the user as a message (task panel, Report view), never as a traceback."""


class UserError(Exception):
    """Something the user can fix: bad selection, bad option, missing module."""


class SelectionError(UserError):
    """The selection holds nothing Pierce can analyse (no solid, an open shell, nothing at all)."""
