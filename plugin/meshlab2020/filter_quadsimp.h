// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
// MeshLab 2020.09 adapter (MeshFilterInterface): Debian's GUI and meshlabserver.
#pragma once

#include <common/interfaces.h>

class QuadsimpFilterPlugin : public QObject, public MeshFilterInterface {
  Q_OBJECT
  MESHLAB_PLUGIN_IID_EXPORTER(MESH_FILTER_INTERFACE_IID)
  Q_INTERFACES(MeshFilterInterface)

 public:
  QuadsimpFilterPlugin();

  QString pluginName() const override;
  QString filterName(FilterIDType filter) const override;
  QString filterInfo(FilterIDType filter) const override;
  FilterClass getClass(QAction* a) override;
  FILTER_ARITY filterArity(QAction* a) const override;
  int getPreConditions(QAction* a) const override;
  int postCondition(QAction* a) const override;
  void initParameterSet(QAction* a, MeshDocument& md, RichParameterList& params) override;
  bool applyFilter(QAction* a, MeshDocument& md, const RichParameterList& params, vcg::CallBackPos* cb) override;

 private:
  bool run(int id, MeshDocument& md, const RichParameterList& params, vcg::CallBackPos* cb);
};
