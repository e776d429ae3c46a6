// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
// MeshLab 2025.07 adapter (FilterPlugin): loaded by pymeshlab 2025.7 with
// pymeshlab.load_plugin().
#pragma once

#include <common/plugins/interfaces/filter_plugin.h>

class QuadsimpFilterPlugin : public QObject, public FilterPlugin {
  Q_OBJECT
  MESHLAB_PLUGIN_IID_EXPORTER(FILTER_PLUGIN_IID)
  Q_INTERFACES(FilterPlugin)

 public:
  QuadsimpFilterPlugin();

  QString pluginName() const override;
  QString filterName(ActionIDType filter) const override;
  QString pythonFilterName(ActionIDType filter) const override;
  QString filterInfo(ActionIDType filter) const override;
  FilterClass getClass(const QAction* a) const override;
  FilterArity filterArity(const QAction* a) const override;
  int getPreConditions(const QAction* a) const override;
  int postCondition(const QAction* a) const override;
  RichParameterList initParameterList(const QAction* a, const MeshDocument& md) override;
  std::map<std::string, QVariant> applyFilter(const QAction* a, const RichParameterList& params, MeshDocument& md,
                                              unsigned int& postConditionMask, vcg::CallBackPos* cb) override;
};
