// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "filter_quadsimp.h"

#include <exception>

#include "filter_runner.h"
#include "filter_specs.h"
#include "layer_conversion.h"
#include "quadsimp/util/errors.h"

using namespace qs::plugin;

QuadsimpFilterPlugin::QuadsimpFilterPlugin() {
  for (const auto& f : filter_specs()) typeList << f.id;
  for (FilterIDType t : types()) actionList << new QAction(filterName(t), this);
}

QString QuadsimpFilterPlugin::pluginName() const { return "FilterQuadsimp"; }

QString QuadsimpFilterPlugin::filterName(FilterIDType f) const { return filter_spec(FilterId(f)).name; }

QString QuadsimpFilterPlugin::filterInfo(FilterIDType f) const {
  return QString::fromStdString(filter_spec(FilterId(f)).info);
}

MeshFilterInterface::FilterClass QuadsimpFilterPlugin::getClass(QAction* a) {
  switch (ID(a)) {
    case kFitmaps: return FilterClass(Quality | VertexColoring);
    case kQuality: return Measure;
    default: return FilterClass(Remeshing | Polygonal);
  }
}

MeshFilterInterface::FILTER_ARITY QuadsimpFilterPlugin::filterArity(QAction* a) const {
  return ID(a) == kQuality ? FIXED : SINGLE_MESH;
}

// No framework precondition: our own check names the layer and says why (a point cloud,
// no faces), where the framework would only say "no faces".
int QuadsimpFilterPlugin::getPreConditions(QAction*) const { return MeshModel::MM_NONE; }

int QuadsimpFilterPlugin::postCondition(QAction* a) const {
  switch (ID(a)) {
    case kConvert: return MeshModel::MM_ALL;
    case kFitmaps: return MeshModel::MM_VERTQUALITY | MeshModel::MM_VERTCOLOR;
    default: return MeshModel::MM_NONE;
  }
}

void QuadsimpFilterPlugin::initParameterSet(QAction* a, MeshDocument& md, RichParameterList& list) {
  const FilterId id = FilterId(ID(a));
  for (const ParamSpec& p : params_of(id)) {
    const QString key = p.key, label = p.label, help = p.help;
    switch (p.kind) {
      case ParamKind::Bool: list.addParam(RichBool(key, p.value != 0, label, help)); break;
      case ParamKind::Float: list.addParam(RichFloat(key, float(p.value), label, help)); break;
      case ParamKind::Int: {
        int def = int(p.value);
        if (def < 0 && md.mm()) def = default_target_faces(md.mm()->cm.fn);
        list.addParam(RichInt(key, def, label, help));
        break;
      }
      case ParamKind::Mesh: list.addParam(RichMesh(key, md.mm(), &md, label, help)); break;
    }
  }
}

bool QuadsimpFilterPlugin::applyFilter(QAction* a, MeshDocument& md, const RichParameterList& params,
                                       vcg::CallBackPos* cb) {
  // Nothing may escape into MeshLab: every failure becomes a log line and `false`.
  try {
    return run(ID(a), md, params, cb);
  } catch (const qs::InvalidInput& e) {
    errorMessage = QString::fromStdString(e.what());
  } catch (const std::invalid_argument& e) {
    errorMessage = QString("Invalid parameters: ") + e.what();
  } catch (const std::exception& e) {
    errorMessage = QString("quadsimp internal error: ") + e.what();
  }
  Log(GLLogStream::FILTER, errorMessage.toStdString());
  return false;
}

bool QuadsimpFilterPlugin::run(int id, MeshDocument& md, const RichParameterList& params, vcg::CallBackPos* cb) {
  MeshModel* m = md.mm();
  if (!m) throw qs::InvalidInput("there is no current mesh");
  const std::string name = m->label().toStdString();
  require_faces(m->cm, name);
  Outcome out;
  switch (id) {
    case kSimplify: {
      const qs::QuadMesh q =
          run_simplification(mesh_file_of(m->cm), name, simplify_params_of(params), progress_of(cb), out);
      MeshModel* result = md.addNewMesh("", m->label() + " quads", true);
      assign_quads(result->cm, q);
      result->UpdateBoxAndNormals();
      break;
    }
    case kConvert: {
      const qs::QuadMesh q = run_conversion(mesh_file_of(m->cm), name, out);
      assign_quads(m->cm, q);
      m->clearDataMask(MeshModel::MM_FACEFACETOPO | MeshModel::MM_VERTFACETOPO);
      m->UpdateBoxAndNormals();
      break;
    }
    case kFitmaps: {
      const qs::Fitmaps f = run_fitmaps(mesh_file_of(m->cm), name, params.getFloat("Tau"), progress_of(cb), out);
      m->updateDataMask(MeshModel::MM_VERTQUALITY);
      store_fitmaps(m->cm, f);
      break;
    }
    case kQuality: {
      MeshModel* ref = params.getMesh("ReferenceMesh");
      if (!ref) throw qs::InvalidInput("choose a reference mesh");
      run_quality(mesh_file_of(m->cm), name, mesh_file_of(ref->cm), ref->label().toStdString(),
                  unsigned(std::max(1000, params.getInt("SampleNum"))), out);
      break;
    }
    default: throw std::invalid_argument("unknown filter");
  }
  for (const std::string& line : out.log) Log(GLLogStream::FILTER, line);
  return true;
}

MESHLAB_PLUGIN_NAME_EXPORTER(QuadsimpFilterPlugin)
