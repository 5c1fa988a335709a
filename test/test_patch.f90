!> Patch tests of the bilinear quadrilateral on a DISTORTED 4 x 4 patch, in
!> axisymmetry and in plane strain.
!>
!> (a) Traction patch: a block on [0, a] x [0, b] loaded by PRESSURE OUTER P=p
!>     and PRESSURE TOP P=q, read from a deck (NODE/ELEMENT cards) and solved by
!>     solve_static. The exact solution is a uniform stress state with a linear
!>     displacement field, which lies in the element space, and 2x2 Gauss
!>     integration is exact for every integrand involved (straight-sided
!>     bilinear quads: B |J| r is a polynomial of degree <= 2 in xi and in
!>     eta; see the notes in displacement_patch). So the discrete solution must
!>     equal it to round-off.
!> (b) Displacement patch: a general linear field prescribed on the boundary
!>     nodes through the library (assemble_stiffness, support_mask,
!>     band_constrain with nonzero values, band_factor, band_solve,
!>     element_strains); the interior nodes must reproduce it and the strains
!>     must be the constant field at every Gauss point, to round-off.
!>
!> Round-off budget used for every "exact" tolerance below: the patch has
!> 25 nodes (50 equations); the constrained stiffness has a condition number
!> of O(1e2..1e4) (measured: see the printed errors, which are ~1e-15..1e-13),
!> so a backward-stable Cholesky solve gives relative errors of about
!> cond * eps ~ 1e-12 at worst. Tolerances of 1e-9 (the brief's figure for
!> stresses) and 1e-10 (displacements, strains) keep a margin of >= 100 over
!> that, while an element that failed the patch test on this distortion
!> (20 % of the element size) would be off by O(1e-3..1e-1) (see the
!> sensitivity check in displacement_patch, which shows a ~1e-2 error).
program test_patch
  use visco2d_kinds, only: dp, geometry_axisymmetric, geometry_plane_strain
  use visco2d_error, only: error_t, error_text
  use visco2d_deck, only: deck_t, read_deck
  use visco2d_static, only: static_solution_t, solve_static
  use visco2d_assembly, only: assemble_stiffness, support_mask, node_dof, gather
  use visco2d_banded, only: band_matrix_t, band_constrain, band_factor, band_solve
  use visco2d_element, only: element_strains, shape_functions, gauss_count, gauss_xi, gauss_eta
  use visco2d_testing, only: check, check_close, test_summary
  implicit none

  character(*), parameter :: folder = 'build/test_decks'
  integer, parameter :: n = 4                      ! n x n elements
  real(dp), parameter :: a = 1.0_dp, b = 1.5_dp    ! patch [0, a] x [0, b], m
  real(dp), parameter :: young = 70.0e9_dp, poisson = 0.33_dp
  real(dp), parameter :: p = 1.0e6_dp, q = 2.5e6_dp  ! OUTER and TOP pressures, Pa

  call execute_command_line('mkdir -p '//folder)

  call traction_patch(geometry_axisymmetric, 'axi')
  call traction_patch(geometry_plane_strain, 'ps')
  call displacement_patch(geometry_axisymmetric, 'axi')
  call displacement_patch(geometry_plane_strain, 'ps')

  call test_summary('test_patch')

contains

  !> Write the distorted patch deck: interior nodes moved irregularly by up to
  !> 20 % of the element size in both directions, boundary (non-corner) nodes
  !> moved by up to 20 % along their edge (so the edge sets stay straight).
  !> Node numbers are sparse (10 k + 1) and elements are written in reverse
  !> order, so the deck reader's sorting and the renumbering are exercised.
  subroutine write_patch_deck(file, geometry)
    character(*), intent(in) :: file
    integer, intent(in) :: geometry
    integer :: unit, i, j, e
    integer(8) :: seed
    real(dp) :: x, y, hx, hy
    character(len=*), parameter :: fmt_node = '(a, i0, 2(1x, es24.16e3))'

    hx = a/n
    hy = b/n
    seed = 20240611_8
    open(newunit=unit, file=file, status='replace', action='write')
    write(unit, '(a)') 'TITLE distorted 4x4 patch'
    write(unit, '(a)') 'ANALYSIS STATIC'
    if (geometry == geometry_axisymmetric) then
      write(unit, '(a)') 'GEOMETRY AXISYMMETRIC'
    else
      write(unit, '(a)') 'GEOMETRY PLANESTRAIN'
    end if
    write(unit, '(a, es24.16, a, f6.3)') 'MATERIAL STEEL ELASTIC E=', young, ' NU=', poisson
    do j = 0, n
      do i = 0, n
        x = i*hx
        y = j*hy
        if (i > 0 .and. i < n) x = x + 0.2_dp*hx*uniform(seed)
        if (j > 0 .and. j < n) y = y + 0.2_dp*hy*uniform(seed)
        if (i == 0) x = 0.0_dp
        if (i == n) x = a
        if (j == 0) y = 0.0_dp
        if (j == n) y = b
        write(unit, fmt_node) 'NODE ', node_number(i, j), x, y
      end do
    end do
    do e = n*n, 1, -1
      i = mod(e - 1, n)
      j = (e - 1)/n
      write(unit, '(a, i0, 4(1x, i0), a)') 'ELEMENT ', 3*e, node_number(i, j), node_number(i + 1, j), &
        node_number(i + 1, j + 1), node_number(i, j + 1), ' MAT=STEEL'
    end do
    write(unit, '(a, es24.16)') 'PRESSURE OUTER P=', p
    write(unit, '(a, es24.16)') 'PRESSURE TOP P=', q
    write(unit, '(a)') 'FIX BOTTOM Z'
    if (geometry == geometry_plane_strain) write(unit, '(a)') 'FIX AXIS R'
    write(unit, '(a)') 'END'
    close(unit)
  end subroutine write_patch_deck

  pure integer function node_number(i, j)
    integer, intent(in) :: i, j
    node_number = 10*(j*(n + 1) + i) + 1
  end function node_number

  !> Deterministic pseudo-random number in [-1, 1] (a 31-bit linear congruential generator).
  real(dp) function uniform(seed)
    integer(8), intent(inout) :: seed
    seed = modulo(1103515245_8*seed + 12345_8, 2147483648_8)
    uniform = 2.0_dp*real(seed, dp)/2147483648.0_dp - 1.0_dp
  end function uniform

  !> Read a patch deck; stop the program if it cannot be read (nothing else can be tested).
  subroutine load_patch(geometry, tag, deck)
    integer, intent(in) :: geometry
    character(*), intent(in) :: tag
    type(deck_t), intent(out) :: deck
    type(error_t), allocatable :: error
    character(:), allocatable :: file
    file = folder//'/test_patch_'//tag//'.inp'
    call write_patch_deck(file, geometry)
    call read_deck(file, deck, error)
    call check('patch '//tag//': deck reads', .not. allocated(error))
    if (allocated(error)) then
      print '(a)', error_text(error)
      call test_summary('test_patch')
      stop 1
    end if
    call check('patch '//tag//': 25 nodes and 16 elements', deck%mesh%nnode == 25 .and. deck%mesh%nelem == 16)
    print '(a, f6.3)', '  patch '//tag//': max |x1 - x2 + x3 - x4| / h = ', max_skew(deck)/(min(a, b)/n)
    call check('patch '//tag//': the mesh is really distorted (some element is far from a parallelogram)', &
               max_skew(deck) > 0.05_dp*min(a, b)/n)
  end subroutine load_patch

  !> Largest |x1 - x2 + x3 - x4| over the elements: zero for a parallelogram mesh
  !> (affine elements, for which the patch test is much weaker).
  real(dp) function max_skew(deck)
    type(deck_t), intent(in) :: deck
    integer :: e
    max_skew = 0.0_dp
    do e = 1, deck%mesh%nelem
      associate (x => deck%mesh%xy(:, deck%mesh%connectivity(:, e)))
      max_skew = max(max_skew, norm2(x(:, 1) - x(:, 2) + x(:, 3) - x(:, 4)))
      end associate
    end do
  end function max_skew

  !> (a) Uniform stress from boundary pressures.
  subroutine traction_patch(geometry, tag)
    integer, intent(in) :: geometry
    character(*), intent(in) :: tag
    type(deck_t) :: deck
    type(static_solution_t) :: solution
    type(error_t), allocatable :: error
    real(dp) :: sigma(4), eps_r, eps_z, stress_error, nodal_error, u_error, u_max, exact(2)
    real(dp) :: reaction_z, reaction_r
    integer :: e, gp, node

    call load_patch(geometry, tag, deck)
    call solve_static(deck%mesh, deck%materials, deck%settings, deck%loads, deck%source, solution, error)
    call check('traction patch '//tag//': solves', .not. allocated(error))
    if (allocated(error)) then
      print '(a)', error_text(error)
      return
    end if

    if (geometry == geometry_axisymmetric) then
      ! sigma_r = sigma_theta = -p (radial equilibrium needs sigma_r = sigma_theta), sigma_z = -q.
      sigma = [-p, -q, -p, 0.0_dp]
    else
      ! Plane strain: eps_zz = 0 gives sigma_zz = nu (sigma_x + sigma_y).
      sigma = [-p, -q, -poisson*(p + q), 0.0_dp]
    end if
    ! Hooke's law (both cases: the third component is sigma_theta or sigma_zz).
    eps_r = (sigma(1) - poisson*(sigma(2) + sigma(3)))/young
    eps_z = (sigma(2) - poisson*(sigma(1) + sigma(3)))/young

    stress_error = 0.0_dp
    do e = 1, deck%mesh%nelem
      do gp = 1, gauss_count
        stress_error = max(stress_error, maxval(abs(solution%stress(:, gp, e) - sigma)))
      end do
    end do
    print '(a, es10.3)', '  traction patch '//tag//': max |sigma - sigma_exact| / p at Gauss points = ', stress_error/p
    ! Round-off: 1e-9 of p (see the budget at the top of the file).
    call check('traction patch '//tag//': every Gauss-point stress is uniform to 1e-9 p', stress_error <= 1.0e-9_dp*p)

    nodal_error = 0.0_dp
    do node = 1, deck%mesh%nnode
      nodal_error = max(nodal_error, maxval(abs(solution%nodal_stress(:, node) - sigma)))
    end do
    ! Extrapolation and averaging of a constant field: also round-off (1e-9 p).
    call check('traction patch '//tag//': nodal (extrapolated, averaged) stress is uniform to 1e-9 p', &
               nodal_error <= 1.0e-9_dp*p)

    u_error = 0.0_dp
    u_max = 0.0_dp
    do node = 1, deck%mesh%nnode
      exact = [eps_r*deck%mesh%xy(1, node), eps_z*deck%mesh%xy(2, node)]
      u_error = max(u_error, maxval(abs(solution%displacement(:, node) - exact)))
      u_max = max(u_max, maxval(abs(exact)))
    end do
    print '(a, es10.3)', '  traction patch '//tag//': max |u - u_exact| / max |u_exact| at nodes      = ', u_error/u_max
    ! Round-off: 1e-10 of the largest displacement.
    call check('traction patch '//tag//': u_r = eps_r r, u_z = eps_z z at every node to 1e-10', &
               u_error <= 1.0e-10_dp*u_max)

    ! Global equilibrium: the supports carry the TOP pressure (z) and, in plane
    ! strain, the OUTER pressure (x, on the AXIS edge). Per radian in axisymmetry:
    ! q * integral_0^a r dr = q a^2 / 2. Round-off (1e-10 relative).
    reaction_z = sum(solution%reaction(2, :))
    reaction_r = sum(solution%reaction(1, :))
    if (geometry == geometry_axisymmetric) then
      call check_close('traction patch axi: total z reaction = q a^2 / 2 (per radian)', reaction_z, &
                       q*a**2/2.0_dp, 1.0e-10_dp)
    else
      call check_close('traction patch ps: total y reaction = q a', reaction_z, q*a, 1.0e-10_dp)
      call check_close('traction patch ps: total x reaction = p b', reaction_r, p*b, 1.0e-10_dp)
    end if
  end subroutine traction_patch

  !> (b) A general linear displacement field imposed on the boundary nodes.
  !>
  !> Plane strain: u = c + A x with a non-symmetric A (rotation + shear):
  !>   strains (A11, A22, 0, A12 + A21), uniform stress, div sigma = 0: no load.
  !> Axisymmetry: a linear field must have u_r = 0 on the axis, so
  !>   u_r = alpha r, u_z = c + beta r + delta z: strains (alpha, delta, alpha, beta).
  !>   This field is NOT equilibrated without load: the z equation of
  !>   equilibrium is d tau/dr + d sigma_z/dz + tau/r + b_z = 0, so the uniform
  !>   shear tau = G beta needs the body force b_z = -tau/r. Its consistent
  !>   nodal load (per radian) is f_z,i = integral N_i b_z r dA = -tau integral N_i dA,
  !>   computed here with 2x2 Gauss (exact: N_i |J| is of degree 2 in xi and eta).
  !>   With that load the interior equations are satisfied exactly by the linear
  !>   field: the internal force of node i, sum_gp B_i^T sigma r |J|, integrates
  !>   sigma_r (r dN/dr + N) + tau r dN/dr + sigma_z r dN/dz + tau r dN/dz, each
  !>   of degree <= 2 in xi and in eta on a straight-sided quad (dN/dr |J| is
  !>   bilinear), so 2x2 Gauss is exact, and integration by parts gives
  !>   -tau integral N_i dA = f_z,i (r-equation: 0).
  subroutine displacement_patch(geometry, tag)
    integer, intent(in) :: geometry
    character(*), intent(in) :: tag
    type(deck_t) :: deck
    type(band_matrix_t) :: stiffness, constrained
    real(dp), allocatable :: shear(:), bulk(:), values(:), load(:), u(:), u_free(:)
    logical, allocatable :: fixed(:), boundary(:)
    real(dp) :: c(2), gradient(2, 2), strain(4), strains(4, gauss_count), field(2)
    real(dp) :: u_error, u_max, strain_error, strain_max, tau, difference
    integer :: e, gp, node, info, interior

    call load_patch(geometry, tag, deck)
    associate (mesh => deck%mesh)
    shear = [(deck%materials(mesh%element_material(e))%shear, e = 1, mesh%nelem)]
    bulk = [(deck%materials(mesh%element_material(e))%bulk, e = 1, mesh%nelem)]

    if (geometry == geometry_plane_strain) then
      c = [1.0e-3_dp, -2.0e-3_dp]
      ! gradient(i, j) = d u_i / d x_j: non-symmetric (A12 = 7e-4, A21 = -4e-4).
      gradient = reshape([2.0e-3_dp, -4.0e-4_dp, 7.0e-4_dp, -1.5e-3_dp], [2, 2])
      strain = [gradient(1, 1), gradient(2, 2), 0.0_dp, gradient(1, 2) + gradient(2, 1)]
    else
      ! u_r = alpha r, u_z = c + beta r + delta z with alpha = 1.2e-3, beta = 8e-4,
      ! c = 5e-4, delta = -9e-4.
      c = [0.0_dp, 5.0e-4_dp]
      gradient = reshape([1.2e-3_dp, 8.0e-4_dp, 0.0_dp, -9.0e-4_dp], [2, 2])
      strain = [gradient(1, 1), gradient(2, 2), gradient(1, 1), gradient(2, 1)]
    end if
    call check('displacement patch '//tag//': the field has shear (gamma /= 0)', abs(strain(4)) > 1.0e-4_dp)

    call assemble_stiffness(deck%mesh, deck%settings, shear, bulk, stiffness)
    ! Boundary nodes: on the sides of the bounding box (they were written exactly there).
    allocate(boundary(mesh%nnode), values(2*mesh%nnode))
    boundary = mesh%xy(1, :) == 0.0_dp .or. mesh%xy(1, :) == a .or. mesh%xy(2, :) == 0.0_dp .or. mesh%xy(2, :) == b
    interior = count(.not. boundary)
    call check('displacement patch '//tag//': 16 boundary and 9 interior nodes', interior == 9)
    fixed = support_mask(deck%mesh, deck%settings, deck%loads)   ! FIX cards + u_r = 0 on the axis in axisymmetry
    do node = 1, mesh%nnode
      field = c + matmul(gradient, mesh%xy(:, node))
      values(node_dof(mesh, node, 1)) = field(1)
      values(node_dof(mesh, node, 2)) = field(2)
      if (boundary(node)) then
        fixed(node_dof(mesh, node, 1)) = .true.
        fixed(node_dof(mesh, node, 2)) = .true.
      end if
    end do
    call check('displacement patch '//tag//': exactly the boundary dofs are constrained', &
               count(fixed) == 2*(mesh%nnode - interior))

    load = body_load(deck)
    if (geometry == geometry_axisymmetric) then
      tau = shear(1)*strain(4)
      load = -tau*load
    else
      load = 0.0_dp
    end if

    u = load
    constrained = stiffness
    call band_constrain(constrained, fixed, values, u)
    call band_factor(constrained, info)
    call check('displacement patch '//tag//': constrained stiffness factors', info == 0)
    if (info /= 0) return
    call band_solve(constrained, u, info)
    call check('displacement patch '//tag//': the factored stiffness solves', info == 0)

    u_error = 0.0_dp
    u_max = maxval(abs(values))
    do node = 1, mesh%nnode
      difference = maxval(abs(u(node_dof(mesh, node, 1):node_dof(mesh, node, 2)) - &
                              values(node_dof(mesh, node, 1):node_dof(mesh, node, 2))))
      u_error = max(u_error, difference)
    end do
    print '(a, es10.3)', '  displacement patch '//tag//': max |u - u_linear| / max |u| over all nodes  = ', &
      u_error/u_max
    ! Round-off (1e-10 of the largest displacement, see the budget at the top).
    call check('displacement patch '//tag//': interior nodes reproduce the linear field to 1e-10', &
               u_error <= 1.0e-10_dp*u_max)

    strain_error = 0.0_dp
    strain_max = maxval(abs(strain))
    do e = 1, mesh%nelem
      strains = element_strains(deck%settings%geometry, mesh%xy(:, mesh%connectivity(:, e)), gather(mesh, e, u))
      do gp = 1, gauss_count
        strain_error = max(strain_error, maxval(abs(strains(:, gp) - strain)))
      end do
    end do
    print '(a, es10.3)', '  displacement patch '//tag//': max |eps - eps_linear| / max |eps| at Gauss pts = ', &
      strain_error/strain_max
    call check('displacement patch '//tag//': strains are the constant field at every Gauss point to 1e-10', &
               strain_error <= 1.0e-10_dp*strain_max)

    ! Sensitivity of the check above: in axisymmetry, solving the same problem
    ! without the equivalent body load of the shear must NOT reproduce the
    ! linear field (the error is of order beta h^2 / |u| ~ 1e-2, eight orders
    ! above the tolerance), which shows the 1e-10 check discriminates.
    if (geometry == geometry_axisymmetric) then
      u_free = 0.0_dp*load
      constrained = stiffness
      call band_constrain(constrained, fixed, values, u_free)
      call band_factor(constrained, info)
      call band_solve(constrained, u_free, info)
      print '(a, es10.3)', '  displacement patch axi: same without the body load tau/r: max |u - u_linear| / max |u| = ', &
        maxval(abs(u_free - values))/u_max
      call check('displacement patch axi: without the body load tau/r the shear field is not reproduced '// &
                 '(error > 1e-6)', maxval(abs(u_free - values)) > 1.0e-6_dp*u_max)
    end if
    end associate
  end subroutine displacement_patch

  !> Vector with, in each z equation, integral N_i dA (area, not r-weighted), 2x2 Gauss.
  function body_load(deck) result(load)
    type(deck_t), intent(in) :: deck
    real(dp), allocatable :: load(:)
    real(dp) :: nshape(4), dn(2, 4), jac(2, 2), detj
    integer :: e, gp, k
    allocate(load(2*deck%mesh%nnode))
    load = 0.0_dp
    associate (mesh => deck%mesh)
    do e = 1, mesh%nelem
      associate (x => mesh%xy(:, mesh%connectivity(:, e)))
      do gp = 1, gauss_count
        call shape_functions(gauss_xi(gp), gauss_eta(gp), nshape, dn)
        jac = matmul(dn, transpose(x))
        detj = jac(1, 1)*jac(2, 2) - jac(1, 2)*jac(2, 1)
        do k = 1, 4
          associate (dof => node_dof(mesh, mesh%connectivity(k, e), 2))
          load(dof) = load(dof) + nshape(k)*detj
          end associate
        end do
      end do
      end associate
    end do
    end associate
  end function body_load
end program test_patch
