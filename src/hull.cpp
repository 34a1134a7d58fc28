// Polytope from a point cloud: qhull (reentrant libqhull_r) computes the hull; the faces go
// through the same validation and coplanar merging as explicit faces, so one path builds them all.
#include <gdcontact/polytope.hpp>

#include <cstdio>
#include <cstdlib>
#include <memory>

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

namespace gdc {
namespace {

// Owns one reentrant qhull instance (no global state: qhull_r keeps everything in qhT).
class QhullRun {
public:
    QhullRun() : errors_(open_memstream(&errorText_, &errorSize_)) { qh_zero(&qh_, errors_); }
    ~QhullRun() {
        int currentLong = 0, totalLong = 0;
        qh_freeqhull(&qh_, !qh_ALL);
        qh_memfreeshort(&qh_, &currentLong, &totalLong);
        if (errors_) std::fclose(errors_);
        std::free(errorText_);
    }
    QhullRun(const QhullRun&) = delete;
    QhullRun& operator=(const QhullRun&) = delete;

    bool run(std::vector<double>& coordinates) {
        char options[] = "qhull Qt";  // triangulated output; coplanar triangles are merged by fromFaces
        int exitCode = qh_new_qhull(&qh_, 3, static_cast<int>(coordinates.size() / 3), coordinates.data(),
                                    False, options, nullptr, errors_);
        return exitCode == 0;
    }
    std::string errorMessage() {
        if (errors_) std::fflush(errors_);
        std::string text = errorText_ ? std::string(errorText_, errorSize_) : std::string();
        auto end = text.find('\n');
        return end == std::string::npos ? text : text.substr(0, end);
    }
    qhT* get() { return &qh_; }

private:
    qhT qh_{};
    char* errorText_ = nullptr;
    std::size_t errorSize_ = 0;
    std::FILE* errors_;
};

}  // namespace

Polytope Polytope::fromPoints(const std::vector<Vec3>& points, const Settings& settings) {
    if (points.size() < 4) throw InvalidInput("a hull needs at least 4 points, got " + std::to_string(points.size()));
    std::vector<double> coordinates;
    coordinates.reserve(points.size() * 3);
    for (std::size_t i = 0; i < points.size(); ++i) {
        if (!points[i].allFinite()) throw InvalidInput("point " + std::to_string(i) + " is not finite");
        coordinates.insert(coordinates.end(), {points[i].x(), points[i].y(), points[i].z()});
    }
    QhullRun qhull;
    if (!qhull.run(coordinates))
        throw InvalidInput("the points have no 3-D hull (collinear, coplanar or coincident): qhull says \"" +
                           qhull.errorMessage() + "\"");
    qhT* qh = qhull.get();
    std::vector<std::vector<int>> faces;
    facetT* facet;
    FORALLfacets {
        std::vector<int> triangle;
        vertexT *vertex, **vertexp;
        FOREACHvertex_(facet->vertices) triangle.push_back(qh_pointid(qh, vertex->point));
        if (triangle.size() != 3) throw InvalidInput("qhull returned a non-triangular facet");
        const Vec3 normal(facet->normal[0], facet->normal[1], facet->normal[2]);
        const Vec3& a = points[triangle[0]];
        if ((points[triangle[1]] - a).cross(points[triangle[2]] - a).dot(normal) < 0)
            std::swap(triangle[1], triangle[2]);  // counter-clockwise seen from outside
        faces.push_back(std::move(triangle));
    }
    return fromFaces(points, faces, settings);
}

}  // namespace gdc
