#include "pqPierceThicknessColoring.h"

#include "pqApplicationCore.h"
#include "pqDataRepresentation.h"
#include "pqPipelineSource.h"
#include "pqServerManagerModel.h"
#include "vtkDataObject.h"
#include "vtkPVArrayInformation.h"
#include "vtkPVDataInformation.h"
#include "vtkPVGeneralSettings.h"
#include "vtkSMPVRepresentationProxy.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMProxy.h"
#include "vtkSMTransferFunctionManager.h"
#include "vtkSMTransferFunctionProxy.h"
#include "vtkSMViewProxy.h"

#include <cmath>
#include <cstring>

namespace
{
// The Pierce Thickness proxy (PierceFilters.xml) and the arrays it writes on its surface output.
constexpr const char* kThicknessProxyName = "PierceThickness";
constexpr const char* kThicknessArray = "Thickness";
constexpr const char* kColorRangeArray = "ThicknessColorRange";
constexpr int kSurfacesPort = 0;

/// The range stored in ThicknessColorRange (one tuple: low, high); false when the output has
/// none or it is empty (no valid thickness anywhere).
bool ColorRangeOf(vtkPVDataInformation* info, double range[2])
{
  vtkPVArrayInformation* array =
    info ? info->GetArrayInformation(kColorRangeArray, vtkDataObject::FIELD) : nullptr;
  if (!array || array->GetNumberOfComponents() != 2)
  {
    return false;
  }
  range[0] = array->GetComponentRange(0)[0];
  range[1] = array->GetComponentRange(1)[1];
  return std::isfinite(range[0]) && std::isfinite(range[1]) && range[0] < range[1];
}
}

//-----------------------------------------------------------------------------
pqPierceThicknessColoring::pqPierceThicknessColoring(QObject* parent)
  : Superclass(parent)
{
}

//-----------------------------------------------------------------------------
pqPierceThicknessColoring::~pqPierceThicknessColoring() = default;

//-----------------------------------------------------------------------------
void pqPierceThicknessColoring::startup()
{
  pqServerManagerModel* model = pqApplicationCore::instance()->getServerManagerModel();
  QObject::connect(
    model, &pqServerManagerModel::sourceAdded, this, &pqPierceThicknessColoring::onSourceAdded);
  // Filters created before the plugin was loaded.
  for (pqPipelineSource* source : model->findItems<pqPipelineSource*>())
  {
    this->onSourceAdded(source);
  }
}

//-----------------------------------------------------------------------------
void pqPierceThicknessColoring::onSourceAdded(pqPipelineSource* source)
{
  const char* name = source && source->getProxy() ? source->getProxy()->GetXMLName() : nullptr;
  if (name && std::strcmp(name, kThicknessProxyName) == 0)
  {
    QObject::connect(source, &pqPipelineSource::representationAdded, this,
      &pqPierceThicknessColoring::onRepresentationAdded, Qt::UniqueConnection);
  }
}

//-----------------------------------------------------------------------------
void pqPierceThicknessColoring::onRepresentationAdded(
  pqPipelineSource*, pqDataRepresentation* repr, int port)
{
  // Only displays that map scalars through a colour map (surface displays in render views), and
  // not those a loaded state creates: they keep the state's colours.
  if (port == kSurfacesPort && repr && !pqApplicationCore::instance()->isLoadingState() &&
    vtkSMPVRepresentationProxy::SafeDownCast(repr->getProxy()) != nullptr)
  {
    // The representation has no data yet: it gets it when the view updates after Apply.
    QObject::connect(repr, &pqDataRepresentation::dataUpdated, this,
      &pqPierceThicknessColoring::onFirstDataUpdate, Qt::UniqueConnection);
  }
}

//-----------------------------------------------------------------------------
void pqPierceThicknessColoring::onFirstDataUpdate()
{
  auto* repr = qobject_cast<pqDataRepresentation*>(this->sender());
  if (!repr)
  {
    return;
  }
  // Once per display: what the user sets afterwards stays.
  QObject::disconnect(repr, &pqDataRepresentation::dataUpdated, this,
    &pqPierceThicknessColoring::onFirstDataUpdate);

  vtkSMProxy* reprProxy = repr->getProxy();
  vtkPVDataInformation* info = repr->getInputDataInformation();
  double range[2];
  if (!ColorRangeOf(info, range))
  {
    return;
  }
  const int association =
    info->GetArrayInformation(kThicknessArray, vtkDataObject::POINT) ? vtkDataObject::POINT
    : info->GetArrayInformation(kThicknessArray, vtkDataObject::CELL) ? vtkDataObject::CELL
                                                                      : -1;
  if (association < 0 ||
    !vtkSMPVRepresentationProxy::SetScalarColoring(reprProxy, kThicknessArray, association))
  {
    return;
  }
  vtkSMProxy* lut = vtkSMPropertyHelper(reprProxy, "LookupTable", /*quiet=*/true).GetAsProxy();
  if (!lut)
  {
    return;
  }
  vtkSMTransferFunctionProxy::RescaleTransferFunction(lut, range[0], range[1], /*extend=*/false);
  if (vtkSMProxy* opacity =
        vtkSMPropertyHelper(lut, "ScalarOpacityFunction", /*quiet=*/true).GetAsProxy())
  {
    vtkSMTransferFunctionProxy::RescaleTransferFunction(opacity, range[0], range[1], false);
  }
  // Apply's "grow and update" would otherwise widen the range to the data's again.
  vtkSMPropertyHelper(lut, "AutomaticRescaleRangeMode", /*quiet=*/true)
    .Set(vtkSMTransferFunctionManager::NEVER);
  lut->UpdateVTKObjects();
  vtkSMViewProxy* view = repr->getViewProxy();
  if (view &&
    vtkPVGeneralSettings::GetInstance()->GetScalarBarMode() ==
      vtkPVGeneralSettings::AUTOMATICALLY_SHOW_AND_HIDE_SCALAR_BARS)
  {
    vtkSMPVRepresentationProxy::SetScalarBarVisibility(reprProxy, view, true);
  }
}
