/**
 * @class   pqPierceThicknessColoring
 * @brief   Colours a new Pierce Thickness display by Thickness over ThicknessColorRange.
 *
 * Started with the ParaView GUI when the PierceParaView plugin loads. When a Pierce Thickness
 * filter's surface output (port 0) is first shown in a render view, usually by the first Apply,
 * the display is coloured by the Thickness array and its colour map is set, once, to the range
 * in the output's field data ThicknessColorRange (Pierce's default range: 0 to 4 x Min Thickness
 * when that is set, else the 2nd to 98th percentile). The colour map's automatic rescaling is
 * then set to Never, so later Applies keep that range; Rescale to Data Range, a custom range, or
 * another automatic rescale mode chosen by the user take over from there. Displays created by
 * loading a state file keep the state's colours. pvpython and pvbatch
 * run no GUI behaviour: see pierce_vtk.show_thickness.
 */
#ifndef pqPierceThicknessColoring_h
#define pqPierceThicknessColoring_h

#include <QObject>

class pqDataRepresentation;
class pqPipelineSource;

class pqPierceThicknessColoring : public QObject
{
  Q_OBJECT
  typedef QObject Superclass;

public:
  pqPierceThicknessColoring(QObject* parent = nullptr);
  ~pqPierceThicknessColoring() override;

  /// Watches the pipeline for Pierce Thickness filters (called when the plugin loads).
  void startup();
  /// Nothing to release: the connections end with the objects they connect.
  void shutdown() {}

private Q_SLOTS:
  void onSourceAdded(pqPipelineSource* source);
  void onRepresentationAdded(pqPipelineSource* source, pqDataRepresentation* repr, int port);
  void onFirstDataUpdate();

private:
  Q_DISABLE_COPY(pqPierceThicknessColoring)
};

#endif
