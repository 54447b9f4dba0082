# Pierce add-on, non-GUI start-up: nothing to register. The analysis logic is the package
# pierce_fc (importable from freecadcmd scripts once this directory is in Mod/); the workbench,
# commands and task panels are set up in InitGui.py.
