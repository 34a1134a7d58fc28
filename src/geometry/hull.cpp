// Polytope from a point cloud: qhull (reentrant libqhull_r) computes the hull; the faces go
// through the same validation and coplanar merging as explicit faces, so one path builds them all.
#include <gdcontact/polytope.hpp>

#include <algorithm>
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
        // Qhull's default merging (C-0): facets coplanar within its rounding are merged into one
        // polygon, so no facet is a sliver of rounding. Triangulated output (Qt) was used before;
        // it splits merged facets into triangles, some of zero area, which fromFaces then had to
        // reject ("face N has zero area" for valid hulls with a tiny cut corner, issue 21).
        char options[] = "qhull";
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
        // The facet's vertices in order around it (qhull orders a 3-d facet's vertices by its
        // ridges); the winding is then made counter-clockwise seen from outside by qhull's normal.
        std::vector<int> loop;
        setT* ordered = qh_facet3vertex(qh, facet);
        vertexT *vertex, **vertexp;
        FOREACHvertex_(ordered) loop.push_back(qh_pointid(qh, vertex->point));
        qh_settempfree(qh, &ordered);
        if (loop.size() < 3) throw InvalidInput("qhull returned a facet with fewer than 3 vertices");
        const Vec3 normal(facet->normal[0], facet->normal[1], facet->normal[2]);
        Vec3 area = Vec3::Zero();  // Newell's normal about the loop's first vertex (its own scale)
        const Vec3& origin = points[loop[0]];
        for (std::size_t i = 1; i + 1 < loop.size(); ++i)
            area += (points[loop[i]] - origin).cross(points[loop[i + 1]] - origin);
        if (area.dot(normal) < 0) std::reverse(loop.begin(), loop.end());
        faces.push_back(std::move(loop));
    }
    // Merging faces within Settings::coplanarTolerance cleans noisy hulls, but must never cost a
    // valid one: a hull thinner than that angle times its width (a tetrahedron 1e-9 of its size
    // high, issue 21) would merge into a flat polygon. Qhull's own facets are then kept — they are
    // convex and planar to qhull's rounding, so they always form a polytope.
    try {
        return fromFaces(points, faces, settings);
    } catch (const InvalidInput&) {
        if (settings.coplanarTolerance == 0) throw;
        Settings unmerged = settings;
        unmerged.coplanarTolerance = 0;
        return fromFaces(points, faces, unmerged);
    }
}

}  // namespace gdc
