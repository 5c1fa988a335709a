!> Element kernels and mesh utilities against exact integrals:
!> shape functions, lumped mass, pressure loads, stiffness symmetry and
!> rigid-body modes, and the bandwidth reduction of the renumbering.
program test_element
  use visco2d_kinds, only: dp, pi, geometry_axisymmetric, geometry_plane_strain
  use visco2d_element, only: shape_functions, element_stiffness, element_lumped_mass, edge_pressure_load
  use visco2d_material, only: elastic_matrix
  use visco2d_mesh_generator, only: rectangle_grid
  use visco2d_renumber, only: reverse_cuthill_mckee, half_bandwidth
  use visco2d_testing, only: check, check_close, test_summary
  use visco2d_deck, only: deck_t, read_deck
  use visco2d_error, only: error_t
  implicit none
  real(dp), parameter :: round_off = 1.0e-13_dp   ! a few ulps of O(1) sums of a handful of terms
  real(dp) :: n(4), dn(2, 4), xy(2, 4), k(8, 8), m(4), f(4), u(8)
  real(dp), allocatable :: grid(:, :)
  integer, allocatable :: connectivity(:, :), edge_element(:), edge_side(:), edge_set(:), position(:)
  integer :: i, before, after

  ! Partition of unity and zero derivative sums at an arbitrary point (eq. [33]).
  call shape_functions(0.3_dp, -0.7_dp, n, dn)
  call check_close('shape functions sum to 1', sum(n), 1.0_dp, round_off)
  call check('shape derivatives sum to 0', all(abs(sum(dn, dim=2)) < round_off))

  ! A distorted quadrilateral off the axis.
  xy = reshape([0.010_dp, 0.000_dp, 0.031_dp, 0.002_dp, 0.028_dp, 0.019_dp, 0.012_dp, 0.022_dp], [2, 4])

  ! Lumped mass per radian equals rho * integral of r dA (exact for a bilinear map:
  ! the integrand r |J| is at most cubic in xi, eta, integrated exactly by 2x2 Gauss).
  m = element_lumped_mass(geometry_axisymmetric, xy, 800.0_dp)
  call check_close('lumped mass = rho * first moment of area (axisymmetric)', sum(m), &
                   800.0_dp*polygon_first_moment(xy), 1.0e-12_dp)
  m = element_lumped_mass(geometry_plane_strain, xy, 800.0_dp)
  call check_close('lumped mass = rho * area (plane strain)', sum(m), 800.0_dp*polygon_area(xy), 1.0e-12_dp)
  call check('lumped masses are positive', all(m > 0.0_dp))

  ! Stiffness: symmetric; a rigid translation in z gives no force in both geometries,
  ! a rigid translation in r only in plane strain (in axisymmetry it strains the hoop).
  k = element_stiffness(geometry_axisymmetric, xy, elastic_matrix(1.0e6_dp, 3.0e6_dp))
  call check('axisymmetric stiffness is symmetric', maxval(abs(k - transpose(k))) <= round_off*maxval(abs(k)))
  u = 0.0_dp
  u(2:8:2) = 1.0_dp
  call check('z translation is force-free (axisymmetric)', maxval(abs(matmul(k, u))) <= 1.0e-10_dp*maxval(abs(k)))
  u = 0.0_dp
  u(1:7:2) = 1.0_dp
  call check('r translation strains the hoop (axisymmetric)', maxval(abs(matmul(k, u))) > 1.0e-3_dp*maxval(abs(k)))
  k = element_stiffness(geometry_plane_strain, xy, elastic_matrix(1.0e6_dp, 3.0e6_dp))
  call check('r translation is force-free (plane strain)', maxval(abs(matmul(k, u))) <= 1.0e-10_dp*maxval(abs(k)))
  u = 0.0_dp
  u(1:7:2) = -xy(2, :)           ! small rotation: u_x = -y, u_y = x
  u(2:8:2) = xy(1, :)
  call check('rotation is force-free (plane strain)', maxval(abs(matmul(k, u))) <= 1.0e-10_dp*maxval(abs(k)))

  ! Uniform pressure on a horizontal top edge from r = a to r = b, per radian:
  ! total force p (b^2 - a^2)/2 downwards (into the body below it).
  f = edge_pressure_load(geometry_axisymmetric, [0.02_dp, 0.01_dp], [0.0_dp, 0.01_dp], 2.0e5_dp)
  call check_close('pressure resultant on an axis edge = p h^2/2', f(2) + f(4), -2.0e5_dp*0.02_dp**2/2, 1.0e-12_dp)
  ! The axis node carries p h^2/6 of it (r-weighted shape functions), not the tributary p h^2/8.
  call check_close('axis node share of a uniform pressure = p h^2/6', f(4), -2.0e5_dp*0.02_dp**2/6, 1.0e-12_dp)
  call check('pressure on a horizontal edge has no radial component', abs(f(1)) + abs(f(3)) < 1.0e-20_dp)

  ! Reverse Cuthill-McKee on a long strip numbered along its length: the
  ! half-bandwidth drops from ~2(NR+1) nodes to a few nodes across the strip.
  call rectangle_grid(0.0_dp, 1.0_dp, 0.0_dp, 0.1_dp, 40, 2, grid, connectivity, edge_element, edge_side, edge_set)
  before = half_bandwidth(connectivity, [(i, i = 1, size(grid, 2))])
  call reverse_cuthill_mckee(size(grid, 2), connectivity, position)
  after = half_bandwidth(connectivity, position)
  print '(a, i0, a, i0)', 'strip 40 x 2 numbered along its length: half-bandwidth before ', before, ', after RCM ', after
  call check('RCM gives a permutation', all(sort_check(position)))
  call check('RCM reduces the bandwidth of a badly numbered strip by at least 4x', 4*after <= before)
  ! RCM is a heuristic: on the same strip numbered across (already optimal,
  ! 9 equations) it gives a little more, so build_mesh keeps the better order.
  call rectangle_grid(0.0_dp, 1.0_dp, 0.0_dp, 0.1_dp, 2, 40, grid, connectivity, edge_element, edge_side, edge_set)
  before = half_bandwidth(connectivity, [(i, i = 1, size(grid, 2))])
  call reverse_cuthill_mckee(size(grid, 2), connectivity, position)
  after = half_bandwidth(connectivity, position)
  print '(a, i0, a, i0)', 'strip 2 x 40 numbered across: half-bandwidth before ', before, ', after RCM ', after
  call check('the across-numbered strip has the optimal half-bandwidth 9', before == 9)
  call check_mesh_keeps_better_order()

  call test_summary('test_element')

contains

  !> build_mesh reports the input and renumbered half-bandwidths and never
  !> makes the bandwidth worse than the input numbering.
  subroutine check_mesh_keeps_better_order()
    type(deck_t) :: deck
    type(error_t), allocatable :: error
    integer :: unit, nr
    do nr = 2, 40, 38
      open(newunit=unit, file='build/test_element_strip.inp', status='replace', action='write')
      write(unit, '(a)') 'ANALYSIS STATIC', 'MATERIAL m ELASTIC E=1e6 NU=0.3'
      write(unit, '(a, i0, a, i0)') 'MESH RECT R0=0 R1=1 Z0=0 Z1=1 NR=', nr, ' NZ=', 42 - nr
      write(unit, '(a)') 'FIX BOTTOM Z', 'END'
      close(unit)
      call read_deck('build/test_element_strip.inp', deck, error)
      call check('strip deck reads', .not. allocated(error))
      if (allocated(error)) return
      print '(a, i0, a, i0, a, i0)', 'mesh NR=', nr, ': half-bandwidth as input ', deck%mesh%half_bandwidth_before, &
        ', used ', deck%mesh%half_bandwidth
      call check('build_mesh never increases the half-bandwidth', &
                 deck%mesh%half_bandwidth <= deck%mesh%half_bandwidth_before)
    end do
    call check('build_mesh renumbers the badly numbered strip (85 -> <= 21)', deck%mesh%half_bandwidth <= 21)
  end subroutine check_mesh_keeps_better_order

  !> True at every position if the array is a permutation of 1..n.
  function sort_check(p) result(ok)
    integer, intent(in) :: p(:)
    logical :: ok(size(p))
    logical :: seen(size(p))
    integer :: j
    seen = .false.
    do j = 1, size(p)
      if (p(j) >= 1 .and. p(j) <= size(p)) seen(p(j)) = .true.
    end do
    ok = seen
  end function sort_check

  !> Area of a polygon (shoelace).
  pure real(dp) function polygon_area(p)
    real(dp), intent(in) :: p(:, :)
    integer :: j, jn
    polygon_area = 0.0_dp
    do j = 1, size(p, 2)
      jn = mod(j, size(p, 2)) + 1
      polygon_area = polygon_area + 0.5_dp*(p(1, j)*p(2, jn) - p(1, jn)*p(2, j))
    end do
  end function polygon_area

  !> Integral of r over a polygon (Green's theorem), the volume per radian.
  pure real(dp) function polygon_first_moment(p)
    real(dp), intent(in) :: p(:, :)
    integer :: j, jn
    real(dp) :: cross
    polygon_first_moment = 0.0_dp
    do j = 1, size(p, 2)
      jn = mod(j, size(p, 2)) + 1
      cross = p(1, j)*p(2, jn) - p(1, jn)*p(2, j)
      polygon_first_moment = polygon_first_moment + (p(1, j) + p(1, jn))*cross/6.0_dp
    end do
  end function polygon_first_moment
end program test_element
