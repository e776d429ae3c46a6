// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "filter_quadsimp.h"

#include <common/mlexception.h>

#include <exception>

#include "apply_filter.h"
#include "qt_images.h"
#include "quadsimp/util/errors.h"

using namespace qs::plugin;

QuadsimpFilterPlugin::QuadsimpFilterPlugin() {
  for (const auto& f : filter_specs()) typeList.push_back(f.id);
  for (ActionIDType t : types()) actionList.push_back(new QAction(filterName(t), this));
}

QString QuadsimpFilterPlugin::pluginName() const { return "FilterQuadsimp"; }

QString QuadsimpFilterPlugin::filterName(ActionIDType f) const { return filter_spec(FilterId(f)).name; }

QString QuadsimpFilterPlugin::pythonFilterName(ActionIDType f) const { return filter_spec(FilterId(f)).python_name; }

QString QuadsimpFilterPlugin::filterInfo(ActionIDType f) const {
  return QString::fromStdString(filter_spec(FilterId(f)).info);
}

FilterPlugin::FilterClass QuadsimpFilterPlugin::getClass(const QAction* a) const {
  switch (ID(a)) {
    case kFitmaps: return FilterClass(Quality | VertexColoring);
    case kQuality: return Measure;
    default: return FilterClass(Remeshing | Polygonal);
  }
}

FilterPlugin::FilterArity QuadsimpFilterPlugin::filterArity(const QAction* a) const {
  return ID(a) == kQuality ? FIXED : SINGLE_MESH;
}

// No framework precondition: our own check names the layer and says why (a point cloud,
// no faces), where the framework would only say "no faces".
int QuadsimpFilterPlugin::getPreConditions(const QAction*) const { return MeshModel::MM_NONE; }

int QuadsimpFilterPlugin::postCondition(const QAction* a) const {
  switch (ID(a)) {
    case kConvert: return MeshModel::MM_ALL;
    case kFitmaps: return MeshModel::MM_VERTQUALITY;
    default: return MeshModel::MM_NONE;
  }
}

RichParameterList QuadsimpFilterPlugin::initParameterList(const QAction* a, const MeshDocument& md) {
  RichParameterList list;
  const MeshModel* current = md.mm();
  for (const ParamSpec& p : params_of(FilterId(ID(a)))) {
    const QString key = p.key, label = p.label, help = p.help;
    switch (p.kind) {
      case ParamKind::Bool: list.addParam(RichBool(key, p.value != 0, label, help)); break;
      case ParamKind::Float: list.addParam(RichFloat(key, Scalarm(p.value), label, help)); break;
      case ParamKind::Int: {
        int def = int(p.value);
        if (def < 0) def = default_target_faces(current ? int(current->cm.fn) : 0);
        list.addParam(RichInt(key, def, label, help));
        break;
      }
      case ParamKind::Mesh: list.addParam(RichMesh(key, current ? current->id() : 0, &md, label, help)); break;
    }
  }
  return list;
}

std::map<std::string, QVariant> QuadsimpFilterPlugin::applyFilter(const QAction* a, const RichParameterList& params,
                                                                  MeshDocument& md, unsigned int& postConditionMask,
                                                                  vcg::CallBackPos* cb) {
  // MeshLab 2025 reports failures through MLException (pymeshlab turns it into a
  // Python exception); nothing else may escape.
  try {
    // MeshLab 2025 keeps textures in memory, by name, with the layer: saving it writes them.
    const auto load = [](MeshModel* m) {
      std::vector<qs::Image> images;
      for (const std::string& name : m->cm.textures) images.push_back(image_of(m->getTexture(name)));
      return images;
    };
    const auto store = [](MeshModel*, MeshModel* quads, std::string& name, const qs::Image& image) {
      quads->clearTextures();
      quads->addTexture(name, qimage_of(image));
      return std::string();
    };
    const Outcome out = apply_filter(
        ID(a), md, params, cb, [](MeshModel* m) { m->updateBoxAndNormals(); },
        [&] { return md.getMesh(params.getMeshId("ReferenceMesh")); }, texture_store(load, store));
    for (const std::string& line : out.log) log(line);
    postConditionMask = postCondition(a);
    std::map<std::string, QVariant> values;
    for (const auto& [k, v] : out.values) values[k] = QVariant(v);
    return values;
  } catch (const qs::InvalidInput& e) {
    throw MLException(QString::fromStdString(e.what()));
  } catch (const std::invalid_argument& e) {
    throw MLException(QString("Invalid parameters: ") + e.what());
  } catch (const MLException&) {
    throw;
  } catch (const std::exception& e) {
    throw MLException(QString("quadsimp internal error: ") + e.what());
  }
}

MESHLAB_PLUGIN_NAME_EXPORTER(QuadsimpFilterPlugin)
