"""Run by the ParaView GUI (paraview --script=pv_gui_plugins.py --exit, under xvfb-run): writes the
plugins the GUI's plugin manager lists (what Tools > Manage Plugins shows), one per line:
name<TAB>file<TAB>loaded, to the file named by $PIERCE_PV_PLUGIN_LIST."""
import os

from paraview import servermanager

info = servermanager.vtkSMProxyManager.GetProxyManager().GetPluginManager().GetLocalInformation()
with open(os.environ["PIERCE_PV_PLUGIN_LIST"], "w") as f:
    for i in range(info.GetNumberOfPlugins()):
        f.write("%s\t%s\t%d\n" % (info.GetPluginName(i), info.GetPluginFileName(i), info.GetPluginLoaded(i)))
