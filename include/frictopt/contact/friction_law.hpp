// SPDX-License-Identifier: MIT
// Friction laws as friction sets W (docs/theory/state-problem.md §1, §3 "Friction sets"): the
// friction resistance q = −τ at a contact node lies in s·W (s = λ for Coulomb), and the
// dissipation is the support function N_W(u_t) = max_{w ∈ W} ⟨w, u_t⟩.
#pragma once

#include <Eigen/Core>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace frictopt::contact {

/// The shape of the friction set W. Spellings in reports and case files come from one table.
enum class FrictionLawKind {
  kInterval,        ///< 2D: W = [−μ₋, μ₊] (direction-dependent when μ₋ ≠ μ₊)
  kDisc,            ///< 3D: W = μ·(unit disc), exact isotropic Coulomb
  kRegularPolygon,  ///< 3D: W = μ·conv{v_j}, φ_j = π(2j−1)/n (docs/theory/state-problem.md §3)
  kPolygon,         ///< 3D: W = conv{μ_j v_j}, per-vertex coefficients (thesis Remark 6.2.1)
  kEllipse,         ///< 3D: W = {(x/μ_x)² + (y/μ_y)² ≤ 1}, exact orthotropic law
  kEllipsePolygon   ///< 3D: W = conv{(μ_x cos φ_j, μ_y sin φ_j)}, vertices on the ellipse
};
/// "interval", "disc", "regular_polygon", "polygon", "ellipse", "ellipse_polygon".
std::string_view to_string(FrictionLawKind kind);
/// Inverse of to_string; throws InvalidInput listing the accepted spellings.
FrictionLawKind parse_friction_law_kind(std::string_view text);

/// A face of the friction set: where a force lies in s·W, or which face a slip direction exposes.
enum class FrictionFace {
  kInterior,    ///< force: strictly inside s·W (stick); slip: u ≈ 0 (no slip direction)
  kEdge,        ///< polygon edge `index` (joins vertices index and index+1 mod n)
  kVertex,      ///< polygon vertex `index` (2D interval: 0 = −μ₋ end, 1 = +μ₊ end)
  kSmooth,      ///< on the smooth boundary of a disc or ellipse
  kDegenerate   ///< s·W collapses to {0} (s ≈ 0 or μ = 0): no face structure
};
/// "interior", "edge", "vertex", "smooth", "degenerate".
std::string_view to_string(FrictionFace face);
/// Inverse of to_string; throws InvalidInput listing the accepted spellings.
FrictionFace parse_friction_face(std::string_view text);

/// A face and, for kEdge / kVertex, its 0-based index (−1 otherwise).
/// Index convention: our vertex j is the thesis' vertex j+1 (φ = π(2j+1)/n), our edge j joins
/// vertices j and j+1 and is crossed by the thesis' ray ρ_{j+1} (docs/theory/sensitivity.md §2–§3).
struct FaceLocation {
  FrictionFace face = FrictionFace::kInterior;
  int index = -1;
  bool operator==(const FaceLocation&) const = default;
};

/// Absolute tolerances of FrictionLaw::classify (ContactState derives them from the solution).
struct ClassificationTolerance {
  double force = 0.0;  ///< distance (units of q) within which q counts as on a face; >= 0
  double slip = 0.0;   ///< |u_t| (units of u) at or below which the node counts as not slipping
  double angle = 1e-8; ///< sin of the angle within which u counts as on an edge-normal ray
};

/// Force face and slip face at one node.
struct FrictionClassification {
  FaceLocation force;  ///< where q lies in s·W
  FaceLocation slip;   ///< face of W exposed by u_t (kInterior when |u_t| <= tolerance.slip)
};

/// A friction law: a compact convex friction set W ⊂ R^{dim−1} containing 0. Value type.
///
/// Tangential vectors are passed as Eigen::Vector2d for both dimensions: in 2D (interval laws)
/// only component 0 is read and results have component 1 = 0; scalar overloads exist for 2D.
/// Polygons are stored counter-clockwise; edge j joins vertices j and j+1 (mod n), has unit
/// outward normal e_j and height h_j = ⟨e_j, w_j⟩ > 0 computed from the actual edge
/// (docs/theory/state-problem.md §3), so linear constraints read ⟨e_j, q⟩ <= s·h_j.
/// All methods are const and thread-safe.
class FrictionLaw {
 public:
  /// 2D law W = [−μ₋, μ₊]: sliding in +e₁ costs μ₊, in −e₁ costs μ₋. Throws InvalidInput
  /// unless both are finite and >= 0.
  static FrictionLaw interval(double mu_minus, double mu_plus);
  /// 3D isotropic disc of radius μ >= 0 (exact Coulomb law).
  static FrictionLaw disc(double mu);
  /// 3D thesis n-gon μ·conv{v_j}, v_j = (cos φ_j, sin φ_j), φ_j = π(2j−1)/n, j = 1..n
  /// (docs/theory/state-problem.md §3). Requires n >= 3, μ >= 0.
  static FrictionLaw regular_polygon(double mu, int n);
  /// 3D anisotropic polygon conv{μ_j v_j} with the n = mu_vertices.size() directions v_j of
  /// regular_polygon (n = 4 is the thesis' Remark 6.2.1). Requires n >= 3, every μ_j finite and
  /// > 0 (or all = 0), and a convex polygon whose every vertex is a corner; otherwise throws
  /// InvalidInput naming the vertex and the offending values.
  static FrictionLaw polygon(std::vector<double> mu_vertices);
  /// 3D exact elliptic law {(x/μ_x)² + (y/μ_y)² <= 1}; μ_x, μ_y > 0 (or both 0).
  static FrictionLaw ellipse(double mu_x, double mu_y);
  /// 3D polygon with vertices (μ_x cos φ_j, μ_y sin φ_j) on the ellipse, φ_j as above.
  static FrictionLaw ellipse_polygon(double mu_x, double mu_y, int n);

  /// The same law turned by `angle` radians counter-clockwise in the tangent plane: W_φ = R(φ)·W
  /// with R(φ) = [[cos φ, −sin φ], [sin φ, cos φ]], so μ_φ(θ) = μ(θ − φ)
  /// (docs/theory/friction-frame.md §1). Polygon vertices and edge normals turn (vertex/edge
  /// indices keep their meaning, heights h_j do not change); a disc or ellipse keeps its semi-axes
  /// in the law's own frame and every method turns its argument into that frame, acts, and turns
  /// the result back. Orientations add up. Throws InvalidInput for a non-finite angle, and for a
  /// nonzero one on a 2D interval law (a 1D tangent line has no rotation).
  FrictionLaw rotated(double angle) const;

  FrictionLawKind kind() const { return kind_; }
  /// Spatial dimension of the contact problem: 2 (interval) or 3.
  int dim() const { return kind_ == FrictionLawKind::kInterval ? 2 : 3; }
  /// Number of tangential components: dim() − 1.
  int tangential_dim() const { return dim() - 1; }
  /// True for interval and polygon laws (faces are vertices and edges); false for the smooth
  /// laws (disc, ellipse), whose boundary has no corners.
  bool is_polygonal() const;
  /// True when W = {0} (all coefficients zero): frictionless.
  bool is_zero() const { return zero_; }
  /// Largest |w| over W (the largest friction coefficient in any direction).
  double max_coefficient() const { return max_coefficient_; }
  /// Vertices w_j (polygons: counter-clockwise; interval: (−μ₋,0), (μ₊,0); smooth sets: none).
  std::span<const Eigen::Vector2d> vertices() const { return vertices_; }
  /// Unit outward normals e_j of edges [w_j, w_{j+1}] (polygons only; empty otherwise).
  std::span<const Eigen::Vector2d> edge_normals() const { return normals_; }
  /// Heights h_j = ⟨e_j, w_j⟩ of the edges (polygons only).
  std::span<const double> edge_heights() const { return heights_; }
  /// Semi-axes (μ_x, μ_y) of an ellipse law; (μ, μ) for a disc. They lie along the columns of
  /// frame(), not along the tangent-plane axes, when orientation() ≠ 0.
  Eigen::Vector2d semi_axes() const { return semi_axes_; }
  /// φ: the angle [rad] by which the law is turned (rotated() sums them; 0 for the factories).
  double orientation() const { return orientation_; }
  /// R(φ): its columns are the law's own axes (the μ_x and μ_y directions) in the tangent plane.
  const Eigen::Matrix2d& frame() const { return frame_; }

  /// Euclidean projection of q onto s·W, s >= 0 (asserted). Exact for every law (ellipse:
  /// Newton on the Lagrange multiplier, converged to rounding).
  Eigen::Vector2d project(const Eigen::Vector2d& q, double s) const;
  double project(double q, double s) const;
  /// Support function N_W(u) = max_{w ∈ W} ⟨w, u⟩ (the dissipation per unit s).
  double support(const Eigen::Vector2d& u) const;
  double support(double u) const;
  /// An element of argmax_{w ∈ W} ⟨w, u⟩ = ∂N_W(u) (for u = 0: the point 0 ∈ W).
  Eigen::Vector2d exposed_point(const Eigen::Vector2d& u) const;
  /// Largest α >= 0 with q + α d ∈ s·W, for q ∈ s·W; +∞ when d = 0.
  double max_step(const Eigen::Vector2d& q, double s, const Eigen::Vector2d& d) const;
  /// Signed boundary offset of q w.r.t. s·W, in units of q: < 0 inside, 0 on the boundary.
  /// Polygons/interval/disc: exact signed distance inside; ellipse: (γ(q) − s)·min(μ_x, μ_y)
  /// with γ the gauge, which has the sign and the scale of the distance.
  double boundary_offset(const Eigen::Vector2d& q, double s) const;
  /// Face of s·W on which q lies, within absolute distance `tolerance`.
  FaceLocation locate(const Eigen::Vector2d& q, double s, double tolerance) const;
  /// The sector of a slip direction u ≠ 0 in the thesis' language (docs/theory/sensitivity.md §2):
  /// the face of W exposed by u. kVertex j when u is in the open cone between e_{j−1} and e_j
  /// (sector S_j, q = λ w_j); kEdge j when u is within sin-angle `angle_tolerance` of e_j (ray
  /// ρ_j); kSmooth for disc and ellipse; kInterior for u = 0.
  FaceLocation sector(const Eigen::Vector2d& u, double angle_tolerance) const;
  /// Force face and slip face at a node (docs/theory/sensitivity.md §3).
  FrictionClassification classify(const Eigen::Vector2d& q, double s, const Eigen::Vector2d& u,
                                  const ClassificationTolerance& tolerance) const;
  /// One line, e.g. "polygon(n=4, mu=[0.3, 0.5, 0.3, 0.5])"; a turned law adds
  /// ", orientation_deg=30".
  std::string describe() const;

  // -------------------------------------------------------------------------------------------
  // Geometry of W and its derivatives (src/contact/friction_law_derivatives.cpp). Every caller
  // that needs a law's local geometry (the adjoint's pieces, the parameter sensitivities, the
  // semismooth Newton engine, identification, orientation design) asks the law, so a new kind
  // is written here once (docs/contact.md, "Adding a friction law").

  /// True when R(φ)·W = W for every turn φ of the tangent plane, so nothing depends on the
  /// law's orientation: a disc, an ellipse with μ_x = μ_y, and W = {0}. Polygons never are (a
  /// regular n-gon is invariant under turns by 2π/n only). 2D: W = −W (μ₋ = μ₊).
  bool is_isotropic() const;
  /// Gauge (Minkowski functional) γ_W(x) = min{t >= 0 : x ∈ t·W}: 1 on the boundary of W,
  /// positively homogeneous, and x ∈ s·W ⇔ γ_W(x) <= s. W = {0}: 0 at x = 0, +∞ elsewhere.
  double gauge(const Eigen::Vector2d& x) const;
  /// Radial function ρ_W(d) = max{t >= 0 : t·d ∈ W} = 1/γ_W(d), d ≠ 0; ρ_W(d)·d is the boundary
  /// point of W in the direction d (dual to support(): N_W(u) = max_d ⟨ρ_W(d) d, u⟩).
  double radial(const Eigen::Vector2d& d) const;

  /// P_W(y) = project(y, 1), one element J of the generalized (Clarke) Jacobian of P_W at y, and
  /// the face P_W(y) lies on.
  struct ProjectionJacobian {
    Eigen::Vector2d point = Eigen::Vector2d::Zero();
    Eigen::Matrix2d jacobian = Eigen::Matrix2d::Zero();
    FaceLocation face{FrictionFace::kDegenerate, -1};
  };
  /// The projection onto W and its Jacobian at y (2D laws read and fill component 0 only):
  ///  - y inside W: J = I, face kInterior;
  ///  - polygon (and interval): J = 0 at a vertex, t tᵀ on an edge with unit tangent t;
  ///  - ellipse {xᵀDx <= 1} in the law's frame, D = diag(1/μ_x², 1/μ_y²) (disc: μ_x = μ_y):
  ///    P_W(y) = (I + γD)⁻¹y with the multiplier γ > 0; implicit differentiation of PᵀDP = 1
  ///    gives J = M − (MDP)(MDP)ᵀ/(PᵀDMDP), M = (I + γD)⁻¹, turned back by R(φ)·J·R(φ)ᵀ;
  ///  - W = {0}: P = 0, J = 0, face kDegenerate.
  /// Projections onto s·W follow by homogeneity: P_{sW}(x) = s·P_W(x/s).
  ProjectionJacobian projection_jacobian(const Eigen::Vector2d& y) const;
  /// ∂w/∂u of the exposed point w(u) = exposed_point(u) = ∇N_W(u). Smooth laws, u ≠ 0:
  /// w(u) = R w₀(Rᵀu) with w₀(d) = A d/√(dᵀAd), A = diag(μ_x², μ_y²), so
  /// ∂w/∂u = R (A/σ − (Ad)(Ad)ᵀ/σ³) Rᵀ, σ = √(dᵀAd), d = Rᵀu. Polygons and the interval: 0 (w is
  /// constant on each open sector; on an edge-normal ray it is not differentiable). u = 0 or
  /// W = {0}: 0.
  Eigen::Matrix2d exposed_point_jacobian(const Eigen::Vector2d& u) const;
  /// ∂w/∂φ at fixed u of the exposed point of rotated(φ): with R' = J R (J the quarter turn),
  /// ∂/∂φ [R w₀(Rᵀu)] = J w(u) − (∂w/∂u) J u. Zero for an isotropic law; for a polygon it is the
  /// turning vertex J w_j (the second term vanishes). 3D laws.
  Eigen::Vector2d exposed_point_orientation_derivative(const Eigen::Vector2d& u) const;

  // -------------------------------------------------------------------------------------------
  // The law's own coefficients c (the factory's arguments) as controls: the friction parameters
  // of the sensitivity module and of identification are these, plus the orientation.

  /// interval (mu_minus, mu_plus); disc and regular_polygon (mu); polygon (mu_vertices[j] =
  /// |w_j|); ellipse and ellipse_polygon (mu_x, mu_y).
  std::vector<std::string> coefficient_names() const;
  /// The values of c, in the order of coefficient_names().
  Eigen::VectorXd coefficients() const;
  /// The law of the same kind and size with coefficients `values`, turned by `orientation` from
  /// the factory's position (rotated(orientation) of the factory's law). Throws InvalidInput for
  /// a wrong count, or as the factory does for bad values.
  FrictionLaw with_coefficients(const Eigen::Ref<const Eigen::VectorXd>& values, double orientation) const;
  /// Polygons and the interval: d[k][j] = ∂w_j/∂c_k, the vertices' derivatives in the tangent
  /// plane (a turned law's coefficients move its vertices along the turned directions R v_j).
  /// Smooth laws: empty.
  std::vector<std::vector<Eigen::Vector2d>> vertex_coefficient_derivatives() const;
  /// ∂w/∂c (2 × coefficients().size()) of the exposed point at fixed u. Smooth laws: the
  /// derivative of R w₀(Rᵀu) by the semi-axes (disc: by μ, both semi-axes together); polygons:
  /// the column of the exposed vertex, d[k][j]; u = 0 or W = {0}: 0.
  Eigen::MatrixXd exposed_point_coefficient_jacobian(const Eigen::Vector2d& u) const;

 private:
  FrictionLaw() = default;
  static FrictionLaw make_polygon(FrictionLawKind kind, std::vector<Eigen::Vector2d> vertices,
                                  std::vector<double> mu_vertices, const char* context);

  /// Throws std::logic_error: a switch over the kinds met a value it does not list (every
  /// per-kind switch ends here instead of treating an unlisted kind as some other one).
  [[noreturn]] static void unknown_kind(FrictionLawKind kind, const char* where);

  // The smooth laws' (disc, ellipse) vectors in the law's own frame and back: Rᵀv and R v.
  Eigen::Vector2d to_law_frame(const Eigen::Vector2d& v) const { return frame_.transpose() * v; }
  Eigen::Vector2d from_law_frame(const Eigen::Vector2d& v) const { return frame_ * v; }

  FrictionLawKind kind_ = FrictionLawKind::kDisc;
  bool zero_ = false;
  double orientation_ = 0.0;
  Eigen::Matrix2d frame_ = Eigen::Matrix2d::Identity();
  double max_coefficient_ = 0.0;
  double min_coefficient_ = 0.0;  // smallest semi-axis / μ_j (used for the ellipse offset)
  Eigen::Vector2d semi_axes_ = Eigen::Vector2d::Zero();
  std::vector<double> mu_vertices_;
  std::vector<Eigen::Vector2d> vertices_;
  std::vector<Eigen::Vector2d> normals_;
  std::vector<double> heights_;
};

}  // namespace frictopt::contact
