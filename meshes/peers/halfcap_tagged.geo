// halfcap.geo (the peers' half cap, unchanged) with its boundary parts named
// as breastsim reads them (src/mesh/user_mesh.hpp): Physical Surface "base"
// (the disc y = 0), "symmetry" (the half disc x = 0) and "skin" (the rest of
// the boundary, the spherical surface). Physical groups do not change the
// mesh: the node and tetrahedron counts are those of halfcap.geo.
// Usage: gmsh -3 halfcap_tagged.geo -setnumber lc 0.00675 -format msh22 -o cap.msh
Include "halfcap.geo";
eps = 1e-6;
big = 2 * R;
base() = Surface In BoundingBox {-eps, -eps, -big, big, eps, big};
symmetry() = Surface In BoundingBox {-eps, -eps, -big, eps, big, big};
skin() = Abs(Boundary{ Volume{3}; });
skin() -= base();
skin() -= symmetry();
Physical Surface("base") = {base()};
Physical Surface("skin") = {skin()};
Physical Surface("symmetry") = {symmetry()};
