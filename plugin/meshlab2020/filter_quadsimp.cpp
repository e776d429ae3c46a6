// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "filter_quadsimp.h"

#include <exception>

#include <QDir>
#include <QFileInfo>

#include "apply_filter.h"
#include "qt_images.h"
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
    // Texture: the GUI loads a layer's texture files after a filter of that class only, and
    // the quads' texture is a file the filter writes (which also lists the filter under
    // Filters > Texture).
    default: return FilterClass(Remeshing | Polygonal | Texture);
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
  // MeshLab 2020.09 keeps textures as file names, relative to the layer's file (or to the
  // working folder) and loads them when it draws. The quads' texture is written beside
  // the input layer's file, as MeshLab's own texture filters write theirs.
  const auto folder_of = [](MeshModel* m) { return m->fullName().isEmpty() ? QDir::currentPath() : m->pathName(); };
  const auto load = [&](MeshModel* m) {
    std::vector<qs::Image> images;
    for (const std::string& name : m->cm.textures) {
      const QString file = QString::fromStdString(name);
      QImage image(QFileInfo(file).isRelative() ? QDir(folder_of(m)).filePath(file) : file);
      if (image.isNull()) image.load(QFileInfo(file).absoluteFilePath());
      images.push_back(image_of(image));
    }
    return images;
  };
  const auto store = [&](MeshModel* input, MeshModel* quads, std::string& name, const qs::Image& image) {
    const QDir folder(folder_of(input));
    const QString stem = QFileInfo(QString::fromStdString(name)).completeBaseName();
    QString file = folder.filePath(QString::fromStdString(name));
    for (int k = 2; QFileInfo::exists(file); ++k) file = folder.filePath(stem + "_" + QString::number(k) + ".png");
    name = QFileInfo(file).fileName().toStdString();
    if (!qimage_of(image).save(file, "PNG")) return "cannot write " + file.toStdString();
    quads->cm.textures = {file.toStdString()};
    return std::string();
  };
  const Outcome out = apply_filter(
      id, md, params, cb, [](MeshModel* m) { m->UpdateBoxAndNormals(); },
      [&] { return params.getMesh("ReferenceMesh"); }, texture_store(load, store));
  for (const std::string& line : out.log) Log(GLLogStream::FILTER, line);
  return true;
}

MESHLAB_PLUGIN_NAME_EXPORTER(QuadsimpFilterPlugin)
