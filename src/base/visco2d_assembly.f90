!> Global assembly shared by every analysis: equation numbering, the banded
!> stiffness S of eq. [25], lumped mass M (eq. [32]), load vectors from
!> pressures and point loads (with their time histories), the support mask
!> and prescribed displacements, and stress recovery to nodes. It takes the
!> mesh, the materials, the settings and the loads (visco2d_model), never
!> the deck they were read from.
module visco2d_assembly
  use visco2d_kinds, only: dp, geometry_axisymmetric
  use visco2d_mesh, only: mesh_t, side_nodes
  use visco2d_material, only: material_t, elastic_matrix
  use visco2d_curve, only: curve_value
  use visco2d_model, only: settings_t, loads_t
  use visco2d_element, only: element_stiffness, element_lumped_mass, edge_pressure_load, &
                             element_internal_force, gauss_to_node_extrapolation
  use visco2d_banded, only: band_matrix_t, band_create, band_add_element
  implicit none
  private

  public :: element_dofs, node_dof, assemble_stiffness, assemble_point_tangents, external_load, support_mask
  public :: prescribed_displacement
  public :: lumped_mass, gravity_load, internal_force, nodal_average, gather, scatter_add, nodal_field, band_vector

contains

  !> Equation number of component c (1 = r, 2 = z) of a node, in band order.
  pure integer function node_dof(mesh, node, component)
    type(mesh_t), intent(in) :: mesh
    integer, intent(in) :: node, component
    node_dof = 2*(mesh%equation(node) - 1) + component
  end function node_dof

  !> The 8 equation numbers of element e: (r1, z1, r2, z2, ...).
  pure function element_dofs(mesh, e) result(dofs)
    type(mesh_t), intent(in) :: mesh
    integer, intent(in) :: e
    integer :: dofs(8)
    integer :: a
    do a = 1, 4
      dofs(2*a - 1) = 2*(mesh%equation(mesh%connectivity(a, e)) - 1) + 1
      dofs(2*a) = dofs(2*a - 1) + 1
    end do
  end function element_dofs

  !> Element displacements (8) gathered from a global vector in band order.
  pure function gather(mesh, e, vector) result(local)
    type(mesh_t), intent(in) :: mesh
    integer, intent(in) :: e
    real(dp), intent(in) :: vector(:)
    real(dp) :: local(8)
    local = vector(element_dofs(mesh, e))
  end function gather

  !> A global vector in band order as (2, nnode) in node order: (u_r, u_z) per node.
  pure function nodal_field(mesh, vector) result(field)
    type(mesh_t), intent(in) :: mesh
    real(dp), intent(in) :: vector(:)
    real(dp) :: field(2, mesh%nnode)
    integer :: node
    do node = 1, mesh%nnode
      field(:, node) = vector(node_dof(mesh, node, 1):node_dof(mesh, node, 2))
    end do
  end function nodal_field

  !> The inverse of nodal_field: a (2, nnode) field in node order as a global vector in band order.
  pure function band_vector(mesh, field) result(vector)
    type(mesh_t), intent(in) :: mesh
    real(dp), intent(in) :: field(:, :)
    real(dp) :: vector(2*mesh%nnode)
    integer :: node
    do node = 1, mesh%nnode
      vector(node_dof(mesh, node, 1):node_dof(mesh, node, 2)) = field(:, node)
    end do
  end function band_vector

  pure subroutine scatter_add(mesh, e, local, vector)
    type(mesh_t), intent(in) :: mesh
    integer, intent(in) :: e
    real(dp), intent(in) :: local(8)
    real(dp), intent(inout) :: vector(:)
    integer :: dofs(8)
    dofs = element_dofs(mesh, e)
    vector(dofs) = vector(dofs) + local
  end subroutine scatter_add

  !> Banded stiffness S = sum_e k_e with per-element moduli (G, K).
  subroutine assemble_stiffness(mesh, settings, shear, bulk, matrix)
    type(mesh_t), intent(in) :: mesh
    type(settings_t), intent(in) :: settings
    real(dp), intent(in) :: shear(:), bulk(:)   !< (nelem)
    type(band_matrix_t), intent(out) :: matrix
    integer :: e
    call band_create(matrix, 2*mesh%nnode, mesh%half_bandwidth)
    do e = 1, mesh%nelem
      call band_add_element(matrix, element_dofs(mesh, e), &
        element_stiffness(settings%geometry, mesh%xy(:, mesh%connectivity(:, e)), elastic_matrix(shear(e), bulk(e)), &
                          settings%formulation))
    end do
  end subroutine assemble_stiffness

  !> The tangent stiffness K_t = sum_e sum_g |J| r B^T C_g B from a material
  !> matrix C_g per Gauss point (a plastic solve's consistent tangents), B and
  !> |J| r the quadrature of the element pass: b (4, 8, gauss, nelem), weight
  !> (gauss, nelem), tangent (4, 4, gauss, nelem).
  subroutine assemble_point_tangents(mesh, b, weight, tangent, matrix)
    type(mesh_t), intent(in) :: mesh
    real(dp), intent(in) :: b(:, :, :, :), weight(:, :), tangent(:, :, :, :)
    type(band_matrix_t), intent(out) :: matrix
    real(dp) :: ke(8, 8)
    integer :: e, g
    call band_create(matrix, 2*mesh%nnode, mesh%half_bandwidth)
    do e = 1, mesh%nelem
      ke = 0.0_dp
      do g = 1, size(weight, 1)
        ke = ke + weight(g, e)*matmul(transpose(b(:, :, g, e)), matmul(tangent(:, :, g, e), b(:, :, g, e)))
      end do
      call band_add_element(matrix, element_dofs(mesh, e), ke)
    end do
  end subroutine assemble_point_tangents

  !> Load vector R(t) of the pressures and point loads at time t (s): each
  !> one's value times its curve (1 without a curve).
  function external_load(mesh, settings, loads, time) result(load)
    type(mesh_t), intent(in) :: mesh
    type(settings_t), intent(in) :: settings
    type(loads_t), intent(in) :: loads
    real(dp), intent(in) :: time
    real(dp) :: load(2*mesh%nnode)
    integer :: k, edge, a, b
    real(dp) :: f(4), factor
    load = 0.0_dp
    do k = 1, size(loads%pressures)
      factor = curve_factor(loads, loads%pressures(k)%curve, time)
      if (factor == 0.0_dp) cycle
      do edge = 1, size(mesh%edge_set)
        if (mesh%edge_set(edge) /= loads%pressures(k)%edge_set) cycle
        call side_nodes(mesh, mesh%edge_element(edge), mesh%edge_side(edge), a, b)
        f = edge_pressure_load(settings%geometry, mesh%xy(:, a), mesh%xy(:, b), factor*loads%pressures(k)%value)
        load(node_dof(mesh, a, 1):node_dof(mesh, a, 2)) = load(node_dof(mesh, a, 1):node_dof(mesh, a, 2)) + f(1:2)
        load(node_dof(mesh, b, 1):node_dof(mesh, b, 2)) = load(node_dof(mesh, b, 1):node_dof(mesh, b, 2)) + f(3:4)
      end do
    end do
    do k = 1, size(loads%forces)
      factor = curve_factor(loads, loads%forces(k)%curve, time)
      a = loads%forces(k)%node
      load(node_dof(mesh, a, 1)) = load(node_dof(mesh, a, 1)) + factor*loads%forces(k)%value(1)
      load(node_dof(mesh, a, 2)) = load(node_dof(mesh, a, 2)) + factor*loads%forces(k)%value(2)
    end do
  end function external_load

  !> Value of curve `curve` of the loads at time t; 1 for curve 0 (constant load).
  pure real(dp) function curve_factor(loads, curve, time) result(factor)
    type(loads_t), intent(in) :: loads
    integer, intent(in) :: curve
    real(dp), intent(in) :: time
    factor = 1.0_dp
    if (curve > 0) factor = curve_value(loads%curves(curve), time)
  end function curve_factor

  !> Prescribed displacement of every supported equation at time t (m): the
  !> values of the supports times their curves (0 for plain supports).
  function prescribed_displacement(mesh, loads, time) result(values)
    type(mesh_t), intent(in) :: mesh
    type(loads_t), intent(in) :: loads
    real(dp), intent(in) :: time
    real(dp) :: values(2*mesh%nnode)
    integer :: k, i, c
    real(dp) :: factor
    values = 0.0_dp
    do k = 1, size(loads%fixes)
      associate (fix => loads%fixes(k))
      if (all(fix%value == 0.0_dp)) cycle
      factor = curve_factor(loads, fix%curve, time)
      do i = 1, size(fix%nodes)
        do c = 1, 2
          if (merge(fix%fix_r, fix%fix_z, c == 1)) values(node_dof(mesh, fix%nodes(i), c)) = factor*fix%value(c)
        end do
      end do
      end associate
    end do
  end function prescribed_displacement

  !> Supported equations: the supports (FIX cards), plus u_r = 0 on the axis in axisymmetry.
  function support_mask(mesh, settings, loads) result(fixed)
    type(mesh_t), intent(in) :: mesh
    type(settings_t), intent(in) :: settings
    type(loads_t), intent(in) :: loads
    logical :: fixed(2*mesh%nnode)
    integer :: k, i, node
    fixed = .false.
    do k = 1, size(loads%fixes)
      do i = 1, size(loads%fixes(k)%nodes)
        node = loads%fixes(k)%nodes(i)
        if (loads%fixes(k)%fix_r) fixed(node_dof(mesh, node, 1)) = .true.
        if (loads%fixes(k)%fix_z) fixed(node_dof(mesh, node, 2)) = .true.
      end do
    end do
    if (settings%geometry == geometry_axisymmetric) then
      do node = 1, mesh%nnode
        if (mesh%xy(1, node) == 0.0_dp) fixed(node_dof(mesh, node, 1)) = .true.
      end do
    end if
  end function support_mask

  !> Lumped (row-sum) mass per equation, eq. [32]. With volume = .true.
  !> the same row sums at unit density, int N_i dV per equation (per radian
  !> in axisymmetry): the weights of a volume average of a nodal field.
  function lumped_mass(mesh, settings, materials, volume) result(mass)
    type(mesh_t), intent(in) :: mesh
    type(settings_t), intent(in) :: settings
    type(material_t), intent(in) :: materials(:)
    logical, intent(in), optional :: volume
    real(dp) :: mass(2*mesh%nnode)
    real(dp) :: m(4), density
    logical :: unit_density
    integer :: e
    unit_density = .false.
    if (present(volume)) unit_density = volume
    mass = 0.0_dp
    do e = 1, mesh%nelem
      density = 1.0_dp
      if (.not. unit_density) density = materials(mesh%element_material(e))%density
      m = element_lumped_mass(settings%geometry, mesh%xy(:, mesh%connectivity(:, e)), density)
      call scatter_add(mesh, e, [m(1), m(1), m(2), m(2), m(3), m(3), m(4), m(4)], mass)
    end do
  end function lumped_mass

  !> Body force of gravity, rho g in -z (loads%gravity, the GRAVITY card):
  !> the consistent load integral N_i rho g dV, which equals the lumped mass
  !> times g because the shape functions sum to one. Zero without gravity.
  function gravity_load(mesh, settings, materials, loads) result(load)
    type(mesh_t), intent(in) :: mesh
    type(settings_t), intent(in) :: settings
    type(material_t), intent(in) :: materials(:)
    type(loads_t), intent(in) :: loads
    real(dp) :: load(2*mesh%nnode)
    load = 0.0_dp
    if (loads%gravity == 0.0_dp) return
    load = lumped_mass(mesh, settings, materials)
    load(1::2) = 0.0_dp
    load(2::2) = -loads%gravity*load(2::2)
  end function gravity_load

  !> Internal force vector sum_e B^T sigma from Gauss-point stresses (4, 4, nelem).
  function internal_force(mesh, settings, stress) result(force)
    type(mesh_t), intent(in) :: mesh
    type(settings_t), intent(in) :: settings
    real(dp), intent(in) :: stress(:, :, :)
    real(dp) :: force(2*mesh%nnode)
    integer :: e
    force = 0.0_dp
    do e = 1, mesh%nelem
      call scatter_add(mesh, e, element_internal_force(settings%geometry, &
        mesh%xy(:, mesh%connectivity(:, e)), stress(:, :, e), settings%formulation), force)
    end do
  end function internal_force

  !> Nodal values of Gauss-point quantities (ncomp, 4, nelem): bilinear
  !> extrapolation in each element, averaged over the elements at a node.
  function nodal_average(mesh, gauss_values) result(nodal)
    type(mesh_t), intent(in) :: mesh
    real(dp), intent(in) :: gauss_values(:, :, :)
    real(dp) :: nodal(size(gauss_values, 1), mesh%nnode)
    real(dp) :: extrapolation(4, 4), count(mesh%nnode)
    integer :: e, a
    extrapolation = gauss_to_node_extrapolation()
    nodal = 0.0_dp
    count = 0.0_dp
    do e = 1, mesh%nelem
      associate (values => matmul(gauss_values(:, :, e), extrapolation))
      do a = 1, 4
        nodal(:, mesh%connectivity(a, e)) = nodal(:, mesh%connectivity(a, e)) + values(:, a)
        count(mesh%connectivity(a, e)) = count(mesh%connectivity(a, e)) + 1.0_dp
      end do
      end associate
    end do
    do a = 1, mesh%nnode
      nodal(:, a) = nodal(:, a)/count(a)
    end do
  end function nodal_average
end module visco2d_assembly
