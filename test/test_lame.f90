!> Lame thick-walled cylinder under internal pressure: a mesh-convergence study.
!>
!> a = 0.1 m, b = 0.2 m, E = 200 GPa, nu = 0.3, p = 100 MPa (INNER, compressive).
!> With A = p a^2 / (b^2 - a^2):
!>   sigma_r = A (1 - b^2/r^2),  sigma_theta = A (1 + b^2/r^2),  sigma_zz = 2 nu A,
!>   u_r = (1 + nu)/E A ((1 - 2 nu) r + b^2/r)          (plane strain, eps_zz = 0).
!>
!> Two models of the same state:
!>  (i)  PLANESTRAIN quarter ring (MESH RING, NT = 2 NR), FIX AXIS R, FIX BOTTOM Z;
!>  (ii) AXISYMMETRIC slice a <= r <= b, 0 <= z <= h (MESH RECT, NZ = 2) with
!>       FIX BOTTOM Z and FIX TOP Z (fixed ends: eps_z = 0, the same plane-strain state).
!> For NR = 4, 8, 16, 32 the test measures the relative L2 error of
!> (sigma_r, sigma_theta) at the Gauss points (analytic values at the Gauss-point
!> radius, volume-weighted by the integration factor |J| or r |J|), the L2 error
!> of sigma_zz, and the bore displacement error max |u_r(a) - u_exact(a)| / u_exact(a).
!> As a stronger regression measure it also reports the L2 error of the
!> element-mean stress (mean of the four Gauss-point stresses) against the
!> analytic stress at the element centre, which is superconvergent, O(h^2).
!>
!> Why the Gauss-point stress error is only O(h) for the bilinear quad: on these
!> meshes u_r is (nearly) linear in r across an element, so e_r = du_r/dr is the
!> same at xi = -1/sqrt(3) and xi = +1/sqrt(3); it is the O(h^2)-accurate
!> centred difference at the element middle, but compared with the analytic
!> value at the Gauss-point radius it is off by |sigma_r'| h / (2 sqrt 3) = O(h).
!> (The 2x2 Gauss points are the Barlow points of the 8-node quad, not of the
!> 4-node one, whose Barlow point is the centre.) So the measured order is
!> 1.00, and the finest mesh needed for the brief's 0.5 % L2 target is NR = 128
!> (0.43 %); NR = 64 and 128 were added to the brief's 4, 8, 16, 32 for that.
program test_lame
  use visco2d_kinds, only: dp, geometry_axisymmetric, geometry_plane_strain
  use visco2d_error, only: error_t, error_text
  use visco2d_deck, only: deck_t, read_deck
  use visco2d_static, only: static_solution_t, solve_static
  use visco2d_element, only: element_gauss_points, strain_displacement, gauss_count, gauss_xi, gauss_eta
  use visco2d_testing, only: check, check_close, test_summary
  use visco2d_strings, only: integer_text, message_real
  implicit none

  character(*), parameter :: folder = 'build/test_decks'
  real(dp), parameter :: ra = 0.1_dp, rb = 0.2_dp, young = 200.0e9_dp, poisson = 0.3_dp, p = 100.0e6_dp
  real(dp), parameter :: big_a = p*ra**2/(rb**2 - ra**2)
  real(dp), parameter :: height = 0.02_dp          ! axisymmetric slice height, m
  integer, parameter :: nmesh = 6
  integer, parameter :: divisions(nmesh) = [4, 8, 16, 32, 64, 128]

  call execute_command_line('mkdir -p '//folder)

  ! Sanity of the analytic solution itself (independent of the FE code): the
  ! boundary conditions sigma_r(a) = -p and sigma_r(b) = 0. Round-off: 1e-14.
  call check_close('analytic: sigma_r(a) = -p', sigma_r_exact(ra), -p, 1.0e-14_dp)
  call check_close('analytic: sigma_r(b) = 0', sigma_r_exact(rb), 0.0_dp, 0.0_dp, 1.0e-14_dp*p)

  call study(geometry_plane_strain, 'ring (plane strain)')
  call study(geometry_axisymmetric, 'rect (axisymmetric, fixed ends)')

  call test_summary('test_lame')

contains

  pure real(dp) function sigma_r_exact(r)
    real(dp), intent(in) :: r
    sigma_r_exact = big_a*(1.0_dp - rb**2/r**2)
  end function sigma_r_exact

  pure real(dp) function sigma_t_exact(r)
    real(dp), intent(in) :: r
    sigma_t_exact = big_a*(1.0_dp + rb**2/r**2)
  end function sigma_t_exact

  pure real(dp) function u_exact(r)
    real(dp), intent(in) :: r
    u_exact = (1.0_dp + poisson)/young*big_a*((1.0_dp - 2.0_dp*poisson)*r + rb**2/r)
  end function u_exact

  subroutine write_deck(file, geometry, nr)
    character(*), intent(in) :: file
    integer, intent(in) :: geometry, nr
    integer :: unit
    open(newunit=unit, file=file, status='replace', action='write')
    write(unit, '(a)') 'TITLE Lame cylinder under internal pressure'
    write(unit, '(a)') 'ANALYSIS STATIC'
    write(unit, '(a, es24.16, a, f6.3)') 'MATERIAL STEEL ELASTIC E=', young, ' NU=', poisson
    if (geometry == geometry_plane_strain) then
      write(unit, '(a)') 'GEOMETRY PLANESTRAIN'
      write(unit, '(a, es24.16, a, es24.16, a, i0, a, i0)') 'MESH RING R0=', ra, ' R1=', rb, ' NR=', nr, ' NT=', 2*nr
      write(unit, '(a)') 'FIX AXIS R'
      write(unit, '(a)') 'FIX BOTTOM Z'
    else
      write(unit, '(a)') 'GEOMETRY AXISYMMETRIC'
      write(unit, '(a, es24.16, a, es24.16, a, es24.16, a, i0, a)') 'MESH RECT R0=', ra, ' R1=', rb, &
        ' Z0=0 Z1=', height, ' NR=', nr, ' NZ=2'
      write(unit, '(a)') 'FIX BOTTOM Z'
      write(unit, '(a)') 'FIX TOP Z'
    end if
    write(unit, '(a, es24.16)') 'PRESSURE INNER P=', p
    write(unit, '(a)') 'END'
    close(unit)
  end subroutine write_deck

  subroutine study(geometry, label)
    integer, intent(in) :: geometry
    character(*), intent(in) :: label
    real(dp) :: stress_error(nmesh), zz_error(nmesh), bore_error(nmesh), order(nmesh), bore_order(nmesh)
    real(dp) :: uz_ratio(nmesh), centre_error(nmesh), centre_order(nmesh), zz_order(nmesh)
    integer :: k, bore_nodes(nmesh)
    logical :: ok
    character(len=8) :: tag

    tag = merge('ring', 'rect', geometry == geometry_plane_strain)
    do k = 1, nmesh
      call one_mesh(geometry, trim(tag), divisions(k), stress_error(k), zz_error(k), centre_error(k), bore_error(k), &
                    bore_nodes(k), uz_ratio(k), ok)
      if (.not. ok) return
      call check(trim(tag)//' NR='//integer_text(divisions(k))//': the bore has NT+1 nodes (ring) or NZ+1 = 3 (slice)', &
                 bore_nodes(k) == merge(2*divisions(k) + 1, 3, geometry == geometry_plane_strain))
    end do
    order = 0.0_dp
    bore_order = 0.0_dp
    centre_order = 0.0_dp
    zz_order = 0.0_dp
    do k = 2, nmesh
      order(k) = log(stress_error(k - 1)/stress_error(k))/log(2.0_dp)
      zz_order(k) = log(zz_error(k - 1)/zz_error(k))/log(2.0_dp)
      centre_order(k) = log(centre_error(k - 1)/centre_error(k))/log(2.0_dp)
      bore_order(k) = log(bore_error(k - 1)/bore_error(k))/log(2.0_dp)
    end do

    print '(a)', ''
    print '(a)', '  Lame convergence, '//label//':'
    print '(a)', '     NR  Gauss L2(sr,st) order   Gauss L2(szz) order   centre L2(sr,st) order   bore du_r/u_r order'
    do k = 1, nmesh
      if (k == 1) then
        print '(3x, i4, 4(3x, es12.4, 3x, a5))', divisions(k), stress_error(k), '  -  ', zz_error(k), '  -  ', &
          centre_error(k), '  -  ', bore_error(k), '  -  '
      else
        print '(3x, i4, 4(3x, es12.4, 3x, f5.3))', divisions(k), stress_error(k), order(k), zz_error(k), zz_order(k), &
          centre_error(k), centre_order(k), bore_error(k), bore_order(k)
      end if
    end do
    print '(a)', ''

    call check(trim(tag)//': stress L2 error decreases monotonically with refinement', &
               all(stress_error(2:) < stress_error(:nmesh - 1)))
    call check(trim(tag)//': bore displacement error decreases monotonically with refinement', &
               all(bore_error(2:) < bore_error(:nmesh - 1)))
    call check(trim(tag)//': centre-stress L2 error decreases monotonically with refinement', &
               all(centre_error(2:) < centre_error(:nmesh - 1)))
    ! Observed orders (the theory is in the header comment):
    !  - Gauss-point stress, O(h): the measured orders are 0.97, 0.99, 1.00, 1.00, 1.00.
    !    Bound 0.9 on every refinement: 0.07 below the coarsest (pre-asymptotic)
    !    measured value; an O(1) consistency error (e.g. an unweighted pressure
    !    load in axisymmetry, tried: orders ~0) fails it. Small consistency
    !    errors hide under the O(h) sampling error here and are caught by the
    !    O(h^2) measures below (a 0.1 % error in e_theta, tried, fails them).
    !  - sigma_zz = nu (sigma_r + sigma_theta) at the Gauss points: same O(h), same bound.
    !  - element-centre stress and bore displacement, O(h^2) (superconvergent
    !    centre, nodal displacement): measured 1.96..2.00; bound 1.8 on the last
    !    three refinements (asymptotic range), which an O(h) defect would fail.
    call check(trim(tag)//': observed Gauss-point stress order >= 0.9 on every refinement', &
               all(order(2:) >= 0.9_dp), 'min order '//message_real(minval(order(2:))))
    call check(trim(tag)//': observed Gauss-point sigma_zz order >= 0.9 on every refinement', &
               all(zz_order(2:) >= 0.9_dp), 'min order '//message_real(minval(zz_order(2:))))
    call check(trim(tag)//': observed element-centre stress order >= 1.8 on the last three refinements', &
               all(centre_order(nmesh - 2:) >= 1.8_dp), 'min order '//message_real(minval(centre_order(nmesh - 2:))))
    call check(trim(tag)//': observed bore displacement order >= 1.8 on the last three refinements', &
               all(bore_order(nmesh - 2:) >= 1.8_dp), 'min order '//message_real(minval(bore_order(nmesh - 2:))))
    ! The brief's accuracy target for the finest mesh: 0.5 % (relative L2 of
    ! (sigma_r, sigma_theta) at the Gauss points, and bore u_r). Not applied to
    ! sigma_zz: sigma_r + sigma_theta = 2A is smaller than |sigma_theta| (up to
    ! 5A), so the same absolute error is a ~2x larger relative error (0.89 % at NR = 128).
    call check(trim(tag)//': finest mesh relative L2 Gauss-point stress error < 0.5 %', stress_error(nmesh) < 5.0e-3_dp)
    call check(trim(tag)//': finest mesh bore u_r error < 0.5 %', bore_error(nmesh) < 5.0e-3_dp)
    if (geometry == geometry_axisymmetric) then
      ! Fixed ends, z-independent load: the FE solution has u_z = 0 at the
      ! mid-height nodes by symmetry (equal element heights, Gauss points
      ! at equal radii above and below), to round-off (1e-10 of u_r).
      call check('rect: u_z = 0 at every node (round-off, 1e-10 of max u_r) on every mesh', all(uz_ratio <= 1.0e-10_dp))
    end if
  end subroutine study

  subroutine one_mesh(geometry, tag, nr, stress_error, zz_error, centre_error, bore_error, bore_nodes, uz_ratio, ok)
    integer, intent(in) :: geometry, nr
    character(*), intent(in) :: tag
    real(dp), intent(out) :: stress_error, zz_error, centre_error, bore_error, uz_ratio
    integer, intent(out) :: bore_nodes
    logical, intent(out) :: ok
    type(deck_t) :: deck
    type(static_solution_t) :: solution
    type(error_t), allocatable :: error
    character(:), allocatable :: file
    real(dp) :: points(2, gauss_count), bmat(4, 8), detj, radius, factor, r, sr, st, szz
    real(dp) :: num, den, num_zz, den_zz, ur, u_max, num_c, den_c, volume, centre(2), mean(4)
    integer :: e, gp, node

    stress_error = huge(1.0_dp); zz_error = huge(1.0_dp); bore_error = huge(1.0_dp); centre_error = huge(1.0_dp)
    uz_ratio = huge(1.0_dp); bore_nodes = 0
    file = folder//'/test_lame_'//tag//'_'//integer_text(nr)//'.inp'
    call write_deck(file, geometry, nr)
    call read_deck(file, deck, error)
    if (.not. allocated(error)) call solve_static(deck%mesh, deck%materials, deck%settings, deck%loads, deck%source, &
      solution, error)
    ok = .not. allocated(error)
    call check(tag//' NR='//integer_text(nr)//': deck reads and solves', ok)
    if (.not. ok) then
      print '(a)', error_text(error)
      return
    end if

    num = 0.0_dp; den = 0.0_dp; num_zz = 0.0_dp; den_zz = 0.0_dp; num_c = 0.0_dp; den_c = 0.0_dp
    associate (mesh => deck%mesh)
    do e = 1, mesh%nelem
      associate (x => mesh%xy(:, mesh%connectivity(:, e)))
      points = element_gauss_points(x)
      volume = 0.0_dp
      do gp = 1, gauss_count
        call strain_displacement(geometry, x, gauss_xi(gp), gauss_eta(gp), bmat, detj, radius, factor)
        call polar(geometry, points(:, gp), solution%stress(:, gp, e), r, sr, st)
        szz = merge(solution%stress(3, gp, e), solution%stress(2, gp, e), geometry == geometry_plane_strain)
        num = num + factor*((sr - sigma_r_exact(r))**2 + (st - sigma_t_exact(r))**2)
        den = den + factor*(sigma_r_exact(r)**2 + sigma_t_exact(r)**2)
        num_zz = num_zz + factor*(szz - 2.0_dp*poisson*big_a)**2
        den_zz = den_zz + factor*(2.0_dp*poisson*big_a)**2
        volume = volume + factor
      end do
      ! Element centre (xi = eta = 0 = the mean of the Gauss points) and the mean Gauss-point stress.
      centre = sum(points, dim=2)/gauss_count
      mean = sum(solution%stress(:, :, e), dim=2)/gauss_count
      call polar(geometry, centre, mean, r, sr, st)
      num_c = num_c + volume*((sr - sigma_r_exact(r))**2 + (st - sigma_t_exact(r))**2)
      den_c = den_c + volume*(sigma_r_exact(r)**2 + sigma_t_exact(r)**2)
      end associate
    end do
    stress_error = sqrt(num/den)
    zz_error = sqrt(num_zz/den_zz)
    centre_error = sqrt(num_c/den_c)

    ! Bore: nodes at distance a from the origin (ring) or at r = a (slice).
    bore_error = 0.0_dp
    u_max = 0.0_dp
    do node = 1, mesh%nnode
      if (geometry == geometry_plane_strain) then
        r = norm2(mesh%xy(:, node))
        ur = dot_product(solution%displacement(:, node), mesh%xy(:, node))/r
      else
        r = mesh%xy(1, node)
        ur = solution%displacement(1, node)
      end if
      u_max = max(u_max, abs(ur))
      if (abs(r - ra) <= 1.0e-12_dp*ra) then
        bore_nodes = bore_nodes + 1
        bore_error = max(bore_error, abs(ur - u_exact(ra))/u_exact(ra))
      end if
    end do
    uz_ratio = maxval(abs(solution%displacement(2, :)))/u_max
    end associate
  end subroutine one_mesh

  !> Radius and (sigma_r, sigma_theta) at a point: plane strain rotates the
  !> Cartesian (x, y, zz, xy) stress to polar axes about the origin;
  !> axisymmetry reads (r, z, theta, rz) directly.
  pure subroutine polar(geometry, point, sig, r, sr, st)
    integer, intent(in) :: geometry
    real(dp), intent(in) :: point(2), sig(4)
    real(dp), intent(out) :: r, sr, st
    real(dp) :: c, s
    if (geometry == geometry_plane_strain) then
      r = norm2(point)
      c = point(1)/r
      s = point(2)/r
      sr = sig(1)*c**2 + sig(2)*s**2 + 2.0_dp*sig(4)*s*c
      st = sig(1)*s**2 + sig(2)*c**2 - 2.0_dp*sig(4)*s*c
    else
      r = point(1)
      sr = sig(1)
      st = sig(3)
    end if
  end subroutine polar
end program test_lame
