!> The static side of the contact extension (PLATE in STATIC), and the
!> Hertz reference, checked against exact answers and hand calculations.
!>
!> 1. Pressure recovery is exact for a uniform pressure. A flat-bottomed block
!>    on PLATE Z=0 SLIP with a uniform PRESSURE p on its top (and the axis, or
!>    in plane strain the plane x = 0, held in r) is in uniaxial stress
!>    sigma_z = -p: a linear displacement field, reproduced exactly by the
!>    bilinear elements, so the plate reactions are exactly the consistent
!>    nodal loads of a uniform pressure p, and force_N = p pi r^2 (p W per
!>    metre in plane strain) to round-off. The axisymmetric axis node carries
!>    p h^2/6 per radian (int (1 - r/h) r dr over the first edge), not the
!>    naive tributary p h^2/8: the naive q = R_axis/(h^2/8) is 4/3 p (printed).
!>    The boundary-mass projection (contact_pressure, on the undeformed
!>    boundary) returns p at every contact node to round-off, on uniform and
!>    graded (NODE/ELEMENT cards) meshes, and q_MPa = p.
!> 2. hertz_impact against the paper's Table 1 (Timoshenko & Goodier row:
!>    1.097 mm, 1.62 ms with 1.47, 2.10 MPa), each within half a unit of the
!>    last printed digit -- with M = rho (4/3) pi R^3 = 0.15543 kg, of which the
!>    printed 0.155 is the rounding -- and its own identities (force, contact
!>    radius, duration, the energy identity (2/5) F_m alpha_m = 1/2 M V^2,
!>    Hertz's q_m = 3 F_m/(2 pi a^2), and the time constant 1.4716 against the
!>    exact integral int_0^1 dx/sqrt(1 - x^(5/2)) = (2/5) B(2/5, 1/2)).
!> 3. Static indentation of the Table-1 sphere (MESH SPHERE levels 3, 4, the
!>    default contact grid) pressed on the plate by GRAVITY G = F/M, a_H/R
!>    from 0.03 to 0.25, against Hertz at the same force. Measured, not
!>    assumed (see the tables): the centroid of the finite sphere approaches
!>    less than Hertz's alpha (the approach of distant points of two
!>    half-spaces), by an amount linear in a/R (level 4: -0.611 a/R + 0.0049,
!>    residuals 0.14 %; the GRADE=2.5 contact grid gave -0.59 a/R + 0.001,
!>    0.39 %, the legacy grid -0.57 a/R - 0.005, 0.15 %).
!> 4. The energy argument: the dynamic Table-1 impact's peak lies on the static
!>    curve (0.8 %), int F d(alpha) along the dynamic history equals
!>    1/2 M V^2 + M g alpha_m (momentum), and the static curve integrated to
!>    alpha_m gives the same energy (0.06-0.26 %; legacy grid 0.16-0.27 %;
!>    against 1/2 M V^2 alone it is 1.8-2.1 % high: gravity's work M g
!>    alpha_m is 2 % of it).
!>
!> (Level 5, 22801 nodes, is not run here: one static solve takes ~36 s.
!> Measured once offline, the deck of press() at F = 193 N: alpha = 1.043676 mm
!> (levels 2, 3, 4: 1.037496, 1.042141, 1.043340), 65 contact nodes, q_MPa =
!> 2.1445 (q_H = 2.1608). On the GRADE=2.5 contact grid: 1.043955 mm (levels
!> 2-4: 1.042451, 1.044351, 1.044498); on the legacy grid: 1.043108 mm (level
!> 4: 1.041725).)
program test_contact_static
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use visco2d_kinds, only: dp, pi
  use visco2d_error, only: error_t, error_text
  use visco2d_deck, only: deck_t, read_deck
  use visco2d_static, only: static_solution_t, solve_static
  use visco2d_contact, only: contact_t, contact_create, contact_held_dofs, contact_pressure
  use visco2d_static_contact, only: solve_static_contact
  use visco2d_hertz, only: hertz_impact, hertz_t, hertz_time_constant
  use visco2d_assembly, only: node_dof, band_vector, lumped_mass
  use visco2d_dynamic, only: solve_dynamic
  use visco2d_record, only: record_t
  use visco2d_expect, only: summary_value
  use visco2d_strings, only: integer_text
  use visco2d_testing, only: check, check_close, test_summary, write_deck, summary_real, exact_text, history_column
  use visco2d_test_decks, only: pressed_sphere
  implicit none

  character(*), parameter :: folder = 'build/test-tmp/test_contact_static'
  ! Table 1 (the paper): V, nu, E, M, R; the fruit's density.
  real(dp), parameter :: speed = 0.9982_dp, poisson = 0.219_dp, young = 18.11e6_dp, mass_paper = 0.155_dp, &
                         radius = 0.0366_dp, density = 756.85_dp, gravity = 9.8_dp
  real(dp), parameter :: modulus = young/(1.0_dp - poisson**2)     ! E* of a sphere on a rigid plate
  real(dp), parameter :: table1_force = 193.0_dp   ! N: the FE peak force of the Table-1 impact (~192-193 N)
  integer, parameter :: nlevel = 2, levels(nlevel) = [3, 4]

  ! Per level: the dynamic peak (force, alpha) and the static table.
  real(dp) :: dyn_force(nlevel), dyn_alpha(nlevel), dyn_mass(nlevel), dyn_work(nlevel), dyn_energy(nlevel)
  real(dp) :: static_alpha_193(nlevel), static_alpha_fm(nlevel), static_work(nlevel), fit_slope(nlevel), &
              fit_intercept(nlevel), fit_residual(nlevel), smallest_dev(nlevel), dev_193(nlevel), q_193(nlevel), &
              q0_193(nlevel), qh_193(nlevel), interpolation_change = 0.0_dp
  integer :: smallest_nodes(nlevel)
  integer :: k

  call execute_command_line('mkdir -p '//folder)

  call pressure_projection()
  call hertz_table1()
  do k = 1, nlevel
    call impact(k)
  end do
  do k = 1, nlevel
    call indentation(k)
  end do
  call convergence()

  call test_summary('test_contact_static')

contains

  real(dp) function ieee_nan()
    ieee_nan = ieee_value(1.0_dp, ieee_quiet_nan)
  end function ieee_nan

  ! ------------------------------------------------------------------------
  ! 1. Pressure projection
  ! ------------------------------------------------------------------------

  subroutine pressure_projection()
    print '(a)', ''
    print '(a)', '## 1. Uniform pressure on a flat-bottomed block on PLATE Z=0 SLIP (q must be p)'
    print '(a)', ''
    print '(a)', '| mesh | contact nodes | undeformed projection: max_i abs(p_i/p - 1) | q_0/p - 1 | '// &
                 'q_MPa/p - 1 (library) | force/(p pi r^2) - 1 | R_axis/(p h^2/6) - 1 | '// &
                 'naive q/p = R_axis/(h^2/8)/p |'
    print '(a)', '|---|---|---|---|---|---|---|---|---|'
    call block('axisymmetric MESH RECT NR=1 NZ=1', .true., [0.0_dp, 0.01_dp], 1, rect=.true.)
    call block('axisymmetric MESH RECT NR=4 NZ=4', .true., [(0.0025_dp*k, k = 0, 4)], 4, rect=.true.)
    call block('axisymmetric MESH RECT NR=10 NZ=5', .true., [(0.001_dp*k, k = 0, 10)], 5, rect=.true.)
    call block('axisymmetric graded r_i = r (i/6)^2, NZ=3', .true., [(0.01_dp*(k/6.0_dp)**2, k = 0, 6)], 3)
    call block('axisymmetric graded r_i = r (i/6)^(1/2), NZ=3', .true., [(0.01_dp*sqrt(k/6.0_dp), k = 0, 6)], 3)
    call block('plane strain MESH RECT NR=4 NZ=4', .false., [(0.0025_dp*k, k = 0, 4)], 4, rect=.true.)
    call block('plane strain graded r_i = W (i/5)^2, NZ=2', .false., [(0.01_dp*(k/5.0_dp)**2, k = 0, 5)], 2)
  end subroutine pressure_projection

  !> A block of width/radius r = 0.01 m (r_nodes(:), 0 .. r), height 0.01 m
  !> (nz rows), E = 5 MPa, nu = 0.3, p = 0.1 MPa on its top, on the plate.
  !> rect: a uniform MESH RECT card (r_nodes then only gives NR); else NODE
  !> and ELEMENT cards at r_nodes.
  subroutine block(name, axisymmetric, r_nodes, nz, rect)
    character(*), intent(in) :: name
    logical, intent(in) :: axisymmetric
    real(dp), intent(in) :: r_nodes(:)
    integer, intent(in) :: nz
    logical, intent(in), optional :: rect
    real(dp), parameter :: p = 1.0e5_dp, width = 0.01_dp, height = 0.01_dp
    character(len=120), allocatable :: lines(:)
    character(:), allocatable :: file, tag
    type(deck_t) :: deck
    type(record_t) :: record
    type(error_t), allocatable :: error
    type(contact_t) :: contact
    type(static_solution_t) :: solution
    real(dp), allocatable :: u(:), reaction(:), values(:), pressure(:)
    logical, allocatable :: held(:)
    real(dp) :: q_lib, q0, force, exact_force, p_dev, axis_dev, naive, h
    integer :: nr, i, j, n, node, axis_node, outer_node, nodes
    integer, save :: count = 0

    count = count + 1
    nr = size(r_nodes) - 1
    file = folder//'/block_'//integer_text(count)//'.inp'
    tag = 'block '//name
    allocate(lines(0))
    lines = [character(len=120) :: 'TITLE block on a plate under a uniform top pressure', 'ANALYSIS STATIC', &
             'GEOMETRY '//trim(merge('AXISYMMETRIC', 'PLANESTRAIN ', axisymmetric)), &
             'MATERIAL block ELASTIC E=5.0e6 NU=0.3']
    if (present(rect)) then
      if (rect) lines = [character(len=120) :: lines, 'MESH RECT R0=0 R1=0.01 Z0=0 Z1=0.01 NR='//integer_text(nr)// &
                         ' NZ='//integer_text(nz)]
    end if
    if (size(lines) == 4) then
      ! Nodes row by row (n = j (nr + 1) + i + 1), elements counter-clockwise.
      do j = 0, nz
        do i = 0, nr
          lines = [character(len=120) :: lines, 'NODE '//integer_text(j*(nr + 1) + i + 1)//' '//exact_text(r_nodes(i + 1))// &
                   ' '//exact_text(height*j/nz)]
        end do
      end do
      do j = 0, nz - 1
        do i = 0, nr - 1
          n = j*(nr + 1) + i + 1
          lines = [character(len=120) :: lines, 'ELEMENT '//integer_text(j*nr + i + 1)//' '//integer_text(n)//' ' &
            //integer_text(n + 1)// &
                   ' '//integer_text(n + nr + 2)//' '//integer_text(n + nr + 1)]
        end do
      end do
    end if
    lines = [character(len=120) :: lines, 'PLATE Z=0 SLIP', 'PRESSURE TOP P=1.0e5']
    ! Plane strain: x = 0 held in r (a symmetry plane; the state has u_x = 0
    ! there). Axisymmetric: the axis is held in r automatically.
    if (.not. axisymmetric) lines = [character(len=120) :: lines, 'FIX AXIS R']
    lines = [character(len=120) :: lines, 'END']
    call write_deck(file, lines)

    call read_deck(file, deck, error)
    if (.not. allocated(error)) call solve_static_contact(deck, record, error)
    call check(tag//': deck reads and solves', .not. allocated(error))
    if (allocated(error)) then
      print '(a)', error_text(error)
      return
    end if
    ! Round-off: the uniaxial state is exact in the element space, so the
    ! errors are those of a small banded solve (~1e-14) and of the summary's
    ! 10 significant digits (5e-10 relative): 1e-9.
    q_lib = 1.0e6_dp*summary_real(record, 'q_MPa')
    force = summary_real(record, 'force_N')
    nodes = nint(summary_real(record, 'contact_nodes'))
    if (axisymmetric) then
      exact_force = p*pi*width**2
    else
      exact_force = p*width
    end if
    call check(tag//': every bottom node is in contact', nodes == nr + 1, 'contact_nodes = '//integer_text(nodes))
    call check_close(tag//': force_N = p pi r^2 (axisymmetric) or p W (plane strain, per m)', force, &
                     exact_force, 1.0e-9_dp)

    ! The same state through the library's pieces, to see every contact node:
    ! the bottom nodes held on the plate, the reactions projected.
    call contact_create(deck, contact)
    associate (mesh => deck%mesh)
    do i = 1, size(contact%candidates)
      node = contact%candidates(i)
      contact%active(node) = mesh%xy(2, node) == 0.0_dp
    end do
    held = contact_held_dofs(deck, contact)
    allocate(values(2*mesh%nnode), u(2*mesh%nnode), reaction(2*mesh%nnode), pressure(mesh%nnode))
    values = 0.0_dp
    call solve_static(deck%mesh, deck%materials, deck%settings, deck%loads, deck%source, solution, error, held, values)
    if (allocated(error)) then
      call check(tag//': direct solve', .false., error_text(error))
      return
    end if
    u = band_vector(mesh, solution%displacement)
    reaction = band_vector(mesh, solution%reaction)
    ! The axis (x = 0) bottom node, the first edge length h, the outer bottom node.
    axis_node = 0
    outer_node = 0
    h = huge(1.0_dp)
    do node = 1, mesh%nnode
      if (mesh%xy(2, node) /= 0.0_dp) cycle
      if (mesh%xy(1, node) == 0.0_dp) then
        axis_node = node
      else
        h = min(h, mesh%xy(1, node))
      end if
      if (abs(mesh%xy(1, node) - width) <= 1.0e-12_dp) outer_node = node
    end do
    ! The projection (on the undeformed boundary): p at every contact node.
    call contact_pressure(deck, contact, reaction, pressure, q0)
    p_dev = maxval(abs(pack(pressure, contact%active)/p - 1.0_dp))
    call check(tag//': projection on the undeformed boundary: p at every contact node (1e-9)', &
               p_dev <= 1.0e-9_dp, 'max |p_i/p - 1| = '//exact_text(p_dev))
    ! The library's q_MPa is that projection's value at the pole: p.
    call check_close(tag//': q_MPa = p', q_lib, p, 1.0e-9_dp)
    if (axisymmetric) then
      ! int_0^h (1 - r/h) r dr = h^2/6 per radian.
      axis_dev = solution%reaction(2, axis_node)/(p*h**2/6.0_dp) - 1.0_dp
      naive = solution%reaction(2, axis_node)/(h**2/8.0_dp)/p
      call check(tag//': axis reaction = p h^2/6 per radian (1e-9)', abs(axis_dev) <= 1.0e-9_dp, exact_text(axis_dev))
      call check_close(tag//': naive tributary q = R_axis/(h^2/8) = 4/3 p', naive, 4.0_dp/3.0_dp, 1.0e-9_dp)
    else
      ! Plane strain: int_0^h (1 - x/h) dx = h/2, the tributary length.
      axis_dev = solution%reaction(2, axis_node)/(p*h/2.0_dp) - 1.0_dp
      naive = solution%reaction(2, axis_node)/(h/2.0_dp)/p
      call check(tag//': edge-node reaction = p h/2 per metre (1e-9)', abs(axis_dev) <= 1.0e-9_dp, exact_text(axis_dev))
    end if
    end associate
    print '(a, i0, a, 5(es10.2, a), f12.9, a)', '| '//name//' | ', nodes, ' | ', p_dev, ' | ', q0/p - 1.0_dp, ' | ', &
      q_lib/p - 1.0_dp, ' | ', force/exact_force - 1.0_dp, ' | ', axis_dev, ' | ', &
      naive, ' |'
  end subroutine block

  ! ------------------------------------------------------------------------
  ! 2. Hertz / Timoshenko-Goodier, eqs. [43]-[45], Table 1
  ! ------------------------------------------------------------------------

  subroutine hertz_table1()
    type(hertz_t) :: hertz, sphere
    real(dp) :: alpha_hand, t_paper, q_hand, exact_constant, a, mass_sphere
    ! The paper prints M = 0.155 kg; its Table-1 row follows from the mass of the
    ! sphere itself, rho (4/3) pi R^3 = 0.155432 kg (0.155 is that rounded): with
    ! M = 0.155 exactly alpha_m = 1.0962 mm (prints 1.096, not 1.097) and
    ! 1.47 alpha_m/V = 1.6143 ms (prints 1.61, not 1.62).
    mass_sphere = density*4.0_dp/3.0_dp*pi*radius**3
    sphere = hertz_impact(young, poisson, radius, mass_sphere, speed)
    hertz = hertz_impact(young, poisson, radius, mass_paper, speed)
    ! By hand, in the paper's form of eq. [43]: alpha = (15 (1 - nu^2) M V^2 / (16 E sqrt R))^0.4.
    alpha_hand = (15.0_dp*(1.0_dp - poisson**2)*mass_paper*speed**2/(16.0_dp*young*sqrt(radius)))**0.4_dp
    t_paper = 1.47_dp*alpha_hand/speed                                           ! eq. [44] as printed
    q_hand = 2.0_dp*young/(pi*(1.0_dp - poisson**2))*sqrt(alpha_hand/radius)     ! eq. [45]
    ! t_m = (alpha_m/V) int_0^1 dx / sqrt(1 - x^(5/2)) (energy: V^2 (1 - (alpha/alpha_m)^(5/2)) = (d alpha/dt)^2),
    ! int_0^1 (1 - x^n)^(-1/2) dx = (1/n) B(1/n, 1/2) = (1/n) Gamma(1/n) Gamma(1/2) / Gamma(1/n + 1/2), n = 5/2.
    exact_constant = 0.4_dp*gamma(0.4_dp)*gamma(0.5_dp)/gamma(0.9_dp)
    a = hertz%contact_radius

    print '(a)', ''
    print '(a)', '## 2. hertz_impact(E=18.11e6, nu=0.219, R=0.0366, V=0.9982) against Table 1 (T&G row)'
    print '(a)', ''
    print '(a)', '| quantity | M = 0.155 kg | M = rho (4/3) pi R^3 = '//exact_text(mass_sphere)//' kg | paper |'
    print '(a)', '|---|---|---|---|'
    print '(a, f9.5, a, f9.5, a)', '| alpha_m (mm) | ', 1.0e3_dp*hertz%alpha_max, ' | ', 1.0e3_dp*sphere%alpha_max, &
      ' | 1.097 |'
    print '(a, f9.5, a, f9.5, a)', '| t_m = 1.47 alpha_m/V (ms) | ', 1.0e3_dp*t_paper, ' | ', &
      1.0e3_dp*1.47_dp*sphere%alpha_max/speed, ' | 1.62 |'
    print '(a, f9.5, a, f9.5, a)', '| t_m = 1.4716 alpha_m/V (ms, hertz_impact) | ', 1.0e3_dp*hertz%t_alpha_max, &
      ' | ', 1.0e3_dp*sphere%t_alpha_max, ' | |'
    print '(a, f9.5, a, f9.5, a)', '| q_m (MPa) | ', 1.0e-6_dp*hertz%q_max, ' | ', 1.0e-6_dp*sphere%q_max, ' | 2.10 |'
    print '(a, f9.4, a, f9.4, a)', '| F_m (N) | ', hertz%force_max, ' | ', sphere%force_max, ' | |'
    print '(a, f9.5, a, f9.5, a)', '| a_m (mm) | ', 1.0e3_dp*hertz%contact_radius, ' | ', &
      1.0e3_dp*sphere%contact_radius, ' | |'
    print '(a, f9.5, a, f9.5, a)', '| 2 t_m (ms) | ', 1.0e3_dp*hertz%duration, ' | ', 1.0e3_dp*sphere%duration, ' | |'
    print '(a, f9.6, a)', '| int_0^1 dx/sqrt(1 - x^2.5) = (2/5) B(2/5, 1/2) | ', exact_constant, &
      ' | (hertz_time_constant 1.4716) | 1.47 |'

    ! The paper's printed row, within half a unit of the last digit, with the sphere's mass.
    call check_close('hertz: alpha_m = 1.097 mm (Table 1), M = rho (4/3) pi R^3', 1.0e3_dp*sphere%alpha_max, &
                     1.097_dp, 0.0_dp, 0.0005_dp)
    call check_close('hertz: q_m = 2.10 MPa (Table 1), M = rho (4/3) pi R^3', 1.0e-6_dp*sphere%q_max, 2.10_dp, &
                     0.0_dp, 0.005_dp)
    call check_close('hertz: 1.47 alpha_m/V = 1.62 ms (Table 1, eq. [44] as printed), M = rho (4/3) pi R^3', &
                     1.0e3_dp*1.47_dp*sphere%alpha_max/speed, 1.62_dp, 0.0_dp, 0.005_dp)
    call check_close('hertz: t_m = 1.4716 alpha_m/V = 1.62 ms, M = rho (4/3) pi R^3', 1.0e3_dp*sphere%t_alpha_max, &
                     1.62_dp, 0.0_dp, 0.005_dp)
    ! With M = 0.155 as printed: q_m and the 1.4716 time still round to the paper's values.
    call check_close('hertz: q_m = 2.10 MPa, M = 0.155', 1.0e-6_dp*hertz%q_max, 2.10_dp, 0.0_dp, 0.005_dp)
    call check_close('hertz: t_m = 1.4716 alpha_m/V = 1.62 ms, M = 0.155', 1.0e3_dp*hertz%t_alpha_max, 1.62_dp, &
                     0.0_dp, 0.005_dp)
    ! The library against the hand formulas (round-off).
    call check_close('hertz: alpha_m = eq. [43] by hand', hertz%alpha_max, alpha_hand, 1.0e-13_dp)
    call check_close('hertz: q_m = eq. [45] by hand', hertz%q_max, q_hand, 1.0e-13_dp)
    call check_close('hertz: t_m = 1.4716 alpha_m / V', hertz%t_alpha_max, 1.4716_dp*alpha_hand/speed, 1.0e-13_dp)
    call check_close('hertz: 1.4716 = (2/5) B(2/5, 1/2) to its 4 decimals', hertz_time_constant, exact_constant, &
                     0.0_dp, 0.5e-4_dp)
    call check_close('hertz: force_max = (4/3) E/(1-nu^2) sqrt(R) alpha_m^1.5', hertz%force_max, &
                     4.0_dp/3.0_dp*young/(1.0_dp - poisson**2)*sqrt(radius)*hertz%alpha_max**1.5_dp, 1.0e-13_dp)
    call check_close('hertz: contact_radius = sqrt(R alpha_m)', hertz%contact_radius, &
                     sqrt(radius*hertz%alpha_max), 1.0e-13_dp)
    call check_close('hertz: duration = 2 t_m', hertz%duration, 2.0_dp*hertz%t_alpha_max, 1.0e-13_dp)
    ! Consistency of the three formulas with each other (not just with themselves):
    ! the work of F = (4/3) E* sqrt(R) alpha^1.5 up to alpha_m is (2/5) F_m alpha_m = 1/2 M V^2,
    ! and Hertz's central pressure 3 F/(2 pi a^2) at a = sqrt(R alpha_m) is eq. [45].
    call check_close('hertz: (2/5) F_m alpha_m = 1/2 M V^2', 0.4_dp*hertz%force_max*hertz%alpha_max, &
                     0.5_dp*mass_paper*speed**2, 1.0e-13_dp)
    call check_close('hertz: 3 F_m / (2 pi a_m^2) = q_m', 1.5_dp*hertz%force_max/(pi*a**2), hertz%q_max, 1.0e-13_dp)
  end subroutine hertz_table1

  ! ------------------------------------------------------------------------
  ! Sphere decks
  ! ------------------------------------------------------------------------

  !> A static indentation deck: the Table-1 sphere at `level` pressed on the plate by G.
  function static_deck(level, g, name) result(file)
    integer, intent(in) :: level
    real(dp), intent(in) :: g
    character(*), intent(in) :: name
    character(:), allocatable :: file
    file = folder//'/'//name//'.inp'
    call write_deck(file, pressed_sphere('Static indentation of the Table-1 sphere on a rigid plate', level, 'SLIP', g))
  end function static_deck

  !> Whole-body mass of the level's sphere mesh (2 pi rho int dV).
  real(dp) function sphere_mass(level) result(mass)
    integer, intent(in) :: level
    type(deck_t) :: deck
    type(error_t), allocatable :: error
    real(dp), allocatable :: weight(:)
    call read_deck(static_deck(level, 1.0_dp, 'mass_'//integer_text(level)), deck, error)
    if (allocated(error)) then
      call check('sphere level '//integer_text(level)//' reads', .false., error_text(error))
      mass = ieee_nan()
      return
    end if
    weight = lumped_mass(deck%mesh, deck%settings, deck%materials, volume=.true.)
    mass = 2.0_dp*pi*density*sum(weight(2::2))
  end function sphere_mass


  ! ------------------------------------------------------------------------
  ! 4a. The dynamic Table-1 impact
  ! ------------------------------------------------------------------------

  subroutine impact(k)
    integer, intent(in) :: k
    character(:), allocatable :: file, tag
    type(deck_t) :: deck
    type(record_t) :: record
    type(error_t), allocatable :: error
    real(dp), allocatable :: alpha(:), force(:)
    integer :: i, peak
    tag = 'impact level '//integer_text(levels(k))
    file = folder//'/impact_'//integer_text(levels(k))//'.inp'
    call write_deck(file, [character(len=80) :: &
      'TITLE Table-1 elastic impact', 'ANALYSIS DYNAMIC', 'GEOMETRY AXISYMMETRIC', &
      'MATERIAL fruit ELASTIC E=18.11e6 NU=0.219 RHO=756.85', 'MESH SPHERE R=0.0366 LEVEL='//integer_text(levels(k)), &
      'PLATE Z=0 SLIP', 'INITIAL VZ=-0.9982 AZ=-9.8', 'GRAVITY G=9.8', 'TIME DT=1e-5 TEND=3e-3', 'END'])
    call read_deck(file, deck, error)
    if (.not. allocated(error)) call solve_dynamic(deck, record, error)
    call check(tag//': deck reads and runs', .not. allocated(error))
    if (allocated(error)) then
      print '(a)', error_text(error)
      dyn_force(k) = ieee_nan()
      dyn_alpha(k) = ieee_nan()
      return
    end if
    dyn_force(k) = summary_real(record, 'force_max_N')
    dyn_alpha(k) = 1.0e-3_dp*summary_real(record, 'alpha_max_mm')
    dyn_mass(k) = summary_real(record, 'body_mass_kg')
    call check_close(tag//': body_mass_kg = 2 pi rho int dV of the mesh', dyn_mass(k), sphere_mass(levels(k)), &
                     1.0e-9_dp)
    ! int F d(alpha) along the history, trapezoid, up to the maximum of alpha.
    alpha = 1.0e-3_dp*history_column(record, 'alpha_mm')
    force = history_column(record, 'force_N')
    peak = maxloc(alpha, dim=1)
    ! alpha_max_mm is the parabola's vertex between steps; the largest sample is alpha_max_step_mm.
    call check_close(tag//': the history maximum of alpha_mm is alpha_max_step_mm', alpha(peak), &
                     1.0e-3_dp*summary_real(record, 'alpha_max_step_mm'), 1.0e-9_dp)
    call check(tag//': the vertex alpha_max_mm is at or above the largest sample', dyn_alpha(k) >= alpha(peak))
    dyn_work(k) = 0.0_dp
    do i = 1, peak - 1
      dyn_work(k) = dyn_work(k) + 0.5_dp*(force(i) + force(i + 1))*(alpha(i + 1) - alpha(i))
    end do
    dyn_energy(k) = 0.5_dp*dyn_mass(k)*speed**2 + dyn_mass(k)*gravity*dyn_alpha(k)
    ! M dv/dt = F - M g for the centre of mass, so int F d(alpha) = 1/2 M V^2 + M g alpha_m
    ! exactly in continuous time (v = 0 at alpha_m); the trapezoid over ~150 steps of a
    ! smooth F(alpha) and Wilson-theta's momentum balance are good to far better than 1 %.
    call check_close(tag//': int F d(alpha) (history, trapezoid) = 1/2 M V^2 + M g alpha_m (1 %)', &
                     dyn_work(k), dyn_energy(k), 0.01_dp)
  end subroutine impact

  ! ------------------------------------------------------------------------
  ! 3 and 4b. Static indentation
  ! ------------------------------------------------------------------------

  subroutine indentation(k)
    integer, intent(in) :: k
    real(dp), allocatable :: targets(:), forces(:), f(:), alpha(:), rc(:), r_out(:), h(:), q(:), q0(:), a_h(:), &
                             dev(:)
    integer, allocatable :: nodes(:), kind(:)
    real(dp) :: mass, alpha_h, q_h, work_static, work_coarse, alpha_fm, slope, intercept, residual
    character(:), allocatable :: tag
    integer :: i, n, i_table, i_dyn
    logical :: monotone

    tag = 'static level '//integer_text(levels(k))
    mass = sphere_mass(levels(k))
    ! Loads: a_H/R = 0.03 .. 0.25 (F = 4 E* a^3 / (3 R)), the FE Table-1 peak force
    ! 193 N (a/R = 0.178), and this level's dynamic peak force. kind: 1 = the
    ! sequence common to both levels, 2 = extra level-3 points, 3 = the dynamic peak.
    targets = [0.03_dp, 0.06_dp, 0.09_dp, 0.12_dp, 0.25_dp]
    kind = [1, 1, 1, 1, 1]
    if (levels(k) == 3) then
      targets = [targets, 0.045_dp, 0.15_dp, 0.21_dp]
      kind = [kind, 2, 2, 2]
    end if
    forces = [4.0_dp*modulus*(targets*radius)**3/(3.0_dp*radius), table1_force, dyn_force(k)]
    kind = [kind, 1, 3]
    call sort(forces, kind)
    n = size(forces)
    allocate(f(n), alpha(n), rc(n), r_out(n), h(n), q(n), q0(n), a_h(n), dev(n), nodes(n))

    print '(a)', ''
    print '(a)', '## 3. Static indentation, MESH SPHERE LEVEL='//integer_text(levels(k))//', PLATE Z=0 SLIP, '// &
                 'GRAVITY G = F/M (M = '//exact_text(mass)//' kg)'
    print '(a)', ''
    print '(a)', '| F (N) | a_H/R | contact nodes | alpha (mm) | alpha_H (mm) | alpha/alpha_H - 1 | '// &
                 'r_c (mm) | r_out (mm) | h (mm) | a_H (mm) | (a_H - r_out)/h | q (MPa) | q_0 (MPa) | q_H (MPa) | '// &
                 'q/q_H - 1 | q_0/q_H - 1 |'
    print '(a)', '|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|'
    do i = 1, n
      call press(levels(k), forces(i)/mass, tag//' F = '//exact_text(forces(i)), f(i), alpha(i), nodes(i), rc(i), &
                 r_out(i), h(i), q(i), q0(i))
      ! Global equilibrium: the plate carries the whole weight M G (summary's 10 digits).
      call check_close(tag//': force_N = M G at F = '//exact_text(forces(i)), f(i), forces(i), 1.0e-9_dp)
      a_h(i) = (3.0_dp*f(i)*radius/(4.0_dp*modulus))**(1.0_dp/3.0_dp)
      alpha_h = (9.0_dp*f(i)**2/(16.0_dp*modulus**2*radius))**(1.0_dp/3.0_dp)
      q_h = 3.0_dp*f(i)/(2.0_dp*pi*a_h(i)**2)
      dev(i) = alpha(i)/alpha_h - 1.0_dp
      print '(a, f9.4, a, f7.4, a, i3, a, 2(f9.5, a), sp, f8.4, ss, a, 4(f7.4, a), f6.2, a, 3(f7.4, a), '// &
            'sp, f8.4, a, f8.4, a)', &
        '| ', f(i), ' | ', a_h(i)/radius, ' | ', nodes(i), ' | ', 1.0e3_dp*alpha(i), ' | ', 1.0e3_dp*alpha_h, ' | ', &
        dev(i), ' | ', 1.0e3_dp*rc(i), ' | ', 1.0e3_dp*r_out(i), ' | ', 1.0e3_dp*h(i), ' | ', 1.0e3_dp*a_h(i), ' | ', &
        (a_h(i) - r_out(i))/h(i), ' | ', 1.0e-6_dp*q(i), ' | ', 1.0e-6_dp*q0(i), ' | ', 1.0e-6_dp*q_h, ' | ', &
        q(i)/q_h - 1.0_dp, ' | ', q0(i)/q_h - 1.0_dp, ' |'
      ! The discrete contact edge lies between the outermost contact node and
      ! the next surface node, [r_out, r_out + h]; Hertz's a must be within one
      ! node spacing of the outermost contact node. Undeformed radii, as in
      ! Hertz's linear theory: the reported contact_radius_mm (r_c) is the
      ! deformed radius, which with SLIP is smaller by the inward slide u_r of
      ! the edge node (~0.16 mm at 193 N, 0.3 h on level 4).
      call check(tag//': |a_H - r_out| <= h (outermost contact node, undeformed) at F = '//exact_text(f(i)), &
                 abs(a_h(i) - r_out(i)) <= h(i), '(a_H - r_out)/h = '//exact_text((a_h(i) - r_out(i))/h(i)))
    end do
    i_table = minloc(abs(f - table1_force), dim=1)
    i_dyn = findloc(kind, 3, dim=1)
    static_alpha_193(k) = alpha(i_table)

    ! Deviation from Hertz against a_H/R: least-squares line over the loads (the dynamic peak excluded).
    call fit_line(pack(a_h/radius, kind /= 3), pack(dev, kind /= 3), slope, intercept, residual)
    print '(a, f8.4, a, sp, f8.4, ss, a, f7.4, a)', '  least squares: alpha/alpha_H - 1 = ', slope, ' a_H/R ', &
      intercept, '   (max |residual| ', residual, ')'
    fit_slope(k) = slope
    fit_intercept(k) = intercept
    fit_residual(k) = residual
    smallest_dev(k) = dev(1)
    smallest_nodes(k) = nodes(1)
    dev_193(k) = dev(i_table)
    q_193(k) = q(i_table)
    q0_193(k) = q0(i_table)
    qh_193(k) = 3.0_dp*f(i_table)/(2.0_dp*pi*a_h(i_table)**2)
    ! (iii) At the Table-1 force (a/R = 0.178) the finite sphere's centroid approaches less than Hertz.
    call check(tag//': at 193 N (a/R = 0.178) alpha < alpha_H (the centroid approaches less than Hertz)', &
               dev(i_table) < 0.0_dp, exact_text(dev(i_table)))
    if (k == nlevel) then
      ! (ii) On the finest level the deviation shrinks monotonically as a/R -> 0 over the
      ! sequence (a/R steps of >= 0.03: the trend, ~0.6 per unit a/R, moves the deviation
      ! by ~2 % per step, more than the ~1 % scatter from the node positions), ...
      monotone = .true.
      do i = 2, n
        if (kind(i) == 3) cycle
        if (kind(i - 1) == 3) then
          if (i > 2) monotone = monotone .and. dev(i) < dev(i - 2)
        else
          monotone = monotone .and. dev(i) < dev(i - 1)
        end if
      end do
      call check(tag//': |alpha/alpha_H - 1| grows monotonically with a/R (shrinks as a/R -> 0)', monotone)
      ! ... and is below 3 % at a/R = 0.03 (4 contact nodes on level 4).
      call check(tag//': |alpha/alpha_H - 1| < 3 % at a/R = 0.03', abs(dev(1)) < 0.03_dp, exact_text(dev(1)))
      call check(tag//': at least 4 contact nodes at a/R = 0.03', nodes(1) >= 4, integer_text(nodes(1)))
      ! Linear in a/R: on level 4 the seven loads lie on a line to 0.14 % (measured;
      ! 0.39 % on the GRADE=2.5 contact grid, 0.15 % on the legacy grid); the bound
      ! 0.5 % guards that, and the intercept (the deviation extrapolated to a/R = 0,
      ! where Hertz is exact) is zero to within the mesh error (at 193 N level 3 is
      ! 0.16 % from the extrapolated limit, below; 0.7 % on the legacy grid) and the
      ! line's own scatter: |intercept| < 0.5 % (measured +0.49 % on the default
      ! grid, close to the bound: the cause of the offset is not established;
      ! +0.06 % on the GRADE=2.5 grid, -0.5 % on the legacy grid).
      call check(tag//': alpha/alpha_H - 1 is linear in a/R (max residual < 0.5 %)', residual < 0.005_dp, &
                 exact_text(residual))
      call check(tag//': the line through the deviations passes within 0.5 % of 0 at a/R = 0', &
                 abs(intercept) < 0.005_dp, exact_text(intercept))
    end if

    ! 4b. The dynamic peak on the static curve: the static alpha at the dynamic peak force.
    alpha_fm = alpha(i_dyn)
    static_alpha_fm(k) = alpha_fm
    print '(a, f9.4, a, f9.6, a, f9.6, a, sp, f8.4, a)', '  dynamic peak force ', dyn_force(k), ' N: static alpha ', &
      1.0e3_dp*alpha_fm, ' mm, dynamic alpha_m ', 1.0e3_dp*dyn_alpha(k), ' mm, static/dynamic - 1 = ', &
      100.0_dp*(alpha_fm/dyn_alpha(k) - 1.0_dp), ' %'
    ! A quasi-static impact lies on the static curve. The impact (~3.2 ms) is not
    ! much longer than the sphere's lowest vibration periods (~0.5-1 ms, c = sqrt(E/rho)
    ! = 155 m/s over 73 mm), so 1 % (the brief's figure) is a test of that, not round-off.
    call check_close(tag//': static alpha at the dynamic peak force = dynamic alpha_m (1 %)', alpha_fm, &
                     dyn_alpha(k), 0.01_dp)
    ! The static curve integrated from 0 to the dynamic alpha_m: the strain energy at
    ! alpha_m of a quasi-static impact, = 1/2 M V^2 + M g alpha_m (gravity's work, 2 %
    ! of 1/2 M V^2, is not negligible). Tolerance 1 %: the static and dynamic states
    ! differ by ~0.8 % in alpha at a given force (above), which moves the integral
    ! by less than that; the power-law interpolation of the sampled curve adds
    ! <~0.1 % (measured on level 3: dense against the level-4 sampling, printed).
    work_static = curve_work(alpha, f, dyn_alpha(k))
    static_work(k) = work_static
    print '(a, es13.6, a, es13.6, a, es13.6, a, sp, f8.4, a, f8.4, a)', '  int_0^alpha_m F_static d(alpha) = ', &
      work_static, ' J; 1/2 M V^2 + M g alpha_m = ', dyn_energy(k), ' J; 1/2 M V^2 = ', 0.5_dp*dyn_mass(k)*speed**2, &
      ' J; ratios - 1: ', 100.0_dp*(work_static/dyn_energy(k) - 1.0_dp), ' %, ', &
      100.0_dp*(work_static/(0.5_dp*dyn_mass(k)*speed**2) - 1.0_dp), ' %'
    if (levels(k) == 3) then
      work_coarse = curve_work(pack(alpha, kind /= 2), pack(f, kind /= 2), dyn_alpha(k))
      print '(a, sp, f8.4, a)', '  interpolation: level-4 sampling of the level-3 curve changes the integral by ', &
        100.0_dp*(work_coarse/work_static - 1.0_dp), ' %'
      interpolation_change = work_coarse/work_static - 1.0_dp
    end if
    call check_close(tag//': int_0^alpha_m F_static d(alpha) = 1/2 M V^2 + M g alpha_m (1 %)', work_static, &
                     dyn_energy(k), 0.01_dp)
    print '(a, es13.6, a, sp, f8.4, a)', '  dynamic int F d(alpha) = ', dyn_work(k), ' J, vs 1/2 M V^2 + M g alpha_m: ', &
      100.0_dp*(dyn_work(k)/dyn_energy(k) - 1.0_dp), ' %'
  end subroutine indentation

  !> One static indentation: solve_static_contact at gravity g, then the same
  !> state rebuilt from its contact set (the nodes left on the plate) with
  !> solve_static, to get the reactions and project them on the undeformed
  !> boundary (q0) as well as on the deformed one (q, the library's q_MPa).
  subroutine press(level, g, tag, force, alpha, nodes, rc, r_out, h, q, q0)
    integer, intent(in) :: level
    real(dp), intent(in) :: g
    character(*), intent(in) :: tag
    real(dp), intent(out) :: force, alpha, rc, r_out, h, q, q0
    integer, intent(out) :: nodes
    type(deck_t) :: deck
    type(record_t) :: record
    type(error_t), allocatable :: error
    type(contact_t) :: contact
    type(static_solution_t) :: solution
    real(dp), allocatable :: u(:), reaction(:), values(:), pressure(:), weight(:), displacement(:, :)
    real(dp) :: q_check, gap
    logical, allocatable :: held(:)
    integer :: i, node
    integer, save :: serial = 0
    serial = serial + 1
    call read_deck(static_deck(level, g, 'static_'//integer_text(serial)), deck, error)
    if (.not. allocated(error)) call solve_static_contact(deck, record, error)
    if (allocated(error)) then
      call check(tag//': solves', .false., error_text(error))
      return
    end if
    force = summary_real(record, 'force_N')
    alpha = 1.0e-3_dp*summary_real(record, 'alpha_mm')
    rc = 1.0e-3_dp*summary_real(record, 'contact_radius_mm')
    q = 1.0e6_dp*summary_real(record, 'q_MPa')
    nodes = nint(summary_real(record, 'contact_nodes'))

    associate (mesh => deck%mesh)
    displacement = record%snapshots(size(record%snapshots))%displacement
    call contact_create(deck, contact)
    r_out = 0.0_dp
    do i = 1, size(contact%candidates)
      node = contact%candidates(i)
      gap = mesh%xy(2, node) + displacement(2, node)
      contact%active(node) = abs(gap) <= contact%tolerance
      if (contact%active(node)) r_out = max(r_out, mesh%xy(1, node))
    end do
    h = huge(1.0_dp)
    do i = 1, size(contact%candidates)
      node = contact%candidates(i)
      if (.not. contact%active(node) .and. mesh%xy(1, node) > r_out .and. mesh%xy(2, node) < radius) &
        h = min(h, mesh%xy(1, node) - r_out)
    end do
    call check(tag//': the nodes on the plate are the contact_nodes', count(contact%active) == nodes)
    held = contact_held_dofs(deck, contact)
    allocate(values(2*mesh%nnode), u(2*mesh%nnode), reaction(2*mesh%nnode), pressure(mesh%nnode))
    values = 0.0_dp
    do i = 1, size(contact%candidates)
      node = contact%candidates(i)
      if (contact%active(node)) values(node_dof(mesh, node, 2)) = -mesh%xy(2, node)
    end do
    call solve_static(deck%mesh, deck%materials, deck%settings, deck%loads, deck%source, solution, error, held, values)
    if (allocated(error)) then
      call check(tag//': rebuilt state solves', .false., error_text(error))
      return
    end if
    u = band_vector(mesh, solution%displacement)
    reaction = band_vector(mesh, solution%reaction)
    weight = lumped_mass(deck%mesh, deck%settings, deck%materials, volume=.true.)
    call check_close(tag//': rebuilt state has the same alpha', -dot_product(weight(2::2), u(2::2))/sum(weight(2::2)), &
                     alpha, 1.0e-8_dp)
    call contact_pressure(deck, contact, reaction, pressure, q_check)
    call check_close(tag//': rebuilt state has the same q_MPa', q_check, q, 1.0e-8_dp)
    u = 0.0_dp
    call contact_pressure(deck, contact, reaction, pressure, q0)
    end associate
  end subroutine press

  !> Least-squares line y = slope x + intercept, and the largest |residual|.
  subroutine fit_line(x, y, slope, intercept, residual)
    real(dp), intent(in) :: x(:), y(:)
    real(dp), intent(out) :: slope, intercept, residual
    real(dp) :: xm, ym
    xm = sum(x)/size(x)
    ym = sum(y)/size(y)
    slope = sum((x - xm)*(y - ym))/sum((x - xm)**2)
    intercept = ym - slope*xm
    residual = maxval(abs(y - slope*x - intercept))
  end subroutine fit_line

  !> int_0^x F d(alpha) of a curve sampled at ascending alpha(:): between samples
  !> (and beyond the last, and from 0 to the first) a power law F = c alpha^m
  !> through the neighbouring samples, integrated exactly.
  real(dp) function curve_work(alpha, f, x) result(work)
    real(dp), intent(in) :: alpha(:), f(:), x
    integer :: i, n
    real(dp) :: m, upper
    n = size(alpha)
    m = log(f(2)/f(1))/log(alpha(2)/alpha(1))
    work = f(1)*alpha(1)/(m + 1.0_dp)*(min(x, alpha(1))/alpha(1))**(m + 1.0_dp)
    do i = 1, n - 1
      if (x <= alpha(i)) exit
      m = log(f(i + 1)/f(i))/log(alpha(i + 1)/alpha(i))
      upper = x
      if (i < n - 1) upper = min(x, alpha(i + 1))
      work = work + f(i)*alpha(i)/(m + 1.0_dp)*((upper/alpha(i))**(m + 1.0_dp) - 1.0_dp)
    end do
  end function curve_work

  !> Sort x ascending, permuting the companion tags alike.
  subroutine sort(x, tags)
    real(dp), intent(inout) :: x(:)
    integer, intent(inout) :: tags(:)
    integer :: i, j, t
    real(dp) :: swap
    do i = 2, size(x)
      do j = i, 2, -1
        if (x(j) >= x(j - 1)) exit
        swap = x(j)
        x(j) = x(j - 1)
        x(j - 1) = swap
        t = tags(j)
        tags(j) = tags(j - 1)
        tags(j - 1) = t
      end do
    end do
  end subroutine sort

  !> (i) Mesh convergence at the Table-1 force, and the summary table.
  subroutine convergence()
    integer :: i
    character(len=12) :: c(nlevel)
    print '(a)', ''
    print '(a)', '## Summary (static indentation and the energy argument; SLIP, Table-1 sphere)'
    print '(a)', ''
    print '(a)', '| quantity | level 3 | level 4 |'
    print '(a)', '|---|---|---|'
    print '(a, 2(f10.6, a))', '| alpha at F = 193 N (mm) [level 5, offline: 1.0437] | ', 1.0e3_dp*static_alpha_193(1), &
      ' | ', 1.0e3_dp*static_alpha_193(2), ' |'
    print '(a, 2(sp, f9.4, a))', '| alpha/alpha_H - 1 at 193 N (a_H/R = 0.178) | ', dev_193(1), ' | ', dev_193(2), ' |'
    print '(a, 2(sp, f9.4, a, ss, i0, a))', '| alpha/alpha_H - 1 at a_H/R = 0.03 (contact nodes) | ', smallest_dev(1), &
      ' (', smallest_nodes(1), ') | ', smallest_dev(2), ' (', smallest_nodes(2), ') |'
    print '(a, 2(f9.4, a))', '| slope d(alpha/alpha_H)/d(a_H/R), least squares | ', fit_slope(1), ' | ', fit_slope(2), ' |'
    print '(a, 2(sp, f9.4, a))', '| intercept at a/R = 0 | ', fit_intercept(1), ' | ', fit_intercept(2), ' |'
    print '(a, 2(f9.4, a))', '| max abs residual of the line | ', fit_residual(1), ' | ', fit_residual(2), ' |'
    print '(a, 2(f9.4, a))', '| q_MPa at 193 N (library) | ', 1.0e-6_dp*q_193(1), ' | ', &
      1.0e-6_dp*q_193(2), ' |'
    print '(a, 2(f9.4, a))', '| q_0 at 193 N (undeformed-boundary projection) | ', 1.0e-6_dp*q0_193(1), ' | ', &
      1.0e-6_dp*q0_193(2), ' |'
    print '(a, 2(f9.4, a))', '| q_H at 193 N | ', 1.0e-6_dp*qh_193(1), ' | ', 1.0e-6_dp*qh_193(2), ' |'
    print '(a, 2(f10.4, a))', '| dynamic force_max_N | ', dyn_force(1), ' | ', dyn_force(2), ' |'
    print '(a, 2(f10.6, a))', '| dynamic alpha_max_mm | ', 1.0e3_dp*dyn_alpha(1), ' | ', 1.0e3_dp*dyn_alpha(2), ' |'
    print '(a, 2(f10.6, a))', '| static alpha at force_max_N (mm) | ', 1.0e3_dp*static_alpha_fm(1), ' | ', &
      1.0e3_dp*static_alpha_fm(2), ' |'
    print '(a, 2(sp, f9.4, a))', '| static / dynamic alpha - 1 (%) | ', 100.0_dp*(static_alpha_fm(1)/dyn_alpha(1) - 1.0_dp), &
      ' | ', 100.0_dp*(static_alpha_fm(2)/dyn_alpha(2) - 1.0_dp), ' |'
    print '(a, 2(f10.6, a))', '| 1/2 M V^2 + M g alpha_m (J) | ', dyn_energy(1), ' | ', dyn_energy(2), ' |'
    print '(a, 2(sp, f9.4, a))', '| dynamic int F d(alpha) / that - 1 (%) | ', 100.0_dp*(dyn_work(1)/dyn_energy(1) - 1.0_dp), &
      ' | ', 100.0_dp*(dyn_work(2)/dyn_energy(2) - 1.0_dp), ' |'
    print '(a, 2(sp, f9.4, a))', '| static int_0^alpha_m F d(alpha) / that - 1 (%) | ', &
      100.0_dp*(static_work(1)/dyn_energy(1) - 1.0_dp), ' | ', 100.0_dp*(static_work(2)/dyn_energy(2) - 1.0_dp), ' |'
    do i = 1, nlevel
      write(c(i), '(sp, f9.4)') 100.0_dp*(static_work(i)/(0.5_dp*dyn_mass(i)*speed**2) - 1.0_dp)
    end do
    print '(a)', '| static int_0^alpha_m F d(alpha) / (1/2 M V^2) - 1 (%) | '//trim(c(1))//' | '//trim(c(2))//' |'
    print '(a, sp, f9.4, a)', '| interpolation error of the static integral (level-4 sampling on level 3, %) | ', &
      100.0_dp*interpolation_change, ' | |'

    ! Levels 3 and 4 at 193 N. On the GRADE=4.5 contact grid the outermost
    ! contact node is the same on levels 2-5 (r = 6.488 mm) and alpha grows
    ! with the level at second order (offline: 1.037496, 1.042141, 1.043340,
    ! 1.043676 mm on levels 2-5, each change 0.26-0.28 of the one before,
    ! p = 1.83; Richardson limit 1.043807 mm): the coarser mesh is stiffer,
    ! checked, and level 3 lies 0.115 % below level 4 and 0.160 % below the
    ! limit. On a monotone sequence |level 3 - level 4| is at most level 3's
    ! distance from the limit: the bound is 0.2 % (0.160 % and a quarter).
    ! (The bound was 0.1 %, measured on the GRADE=2.5 grid: 0.014 %, but
    ! there the contact edge jittered, level 5 0.052 % below level 4, and the
    ! ordering was not checked; on the legacy grid 0.72 % against 1 %.)
    call check_close('static: alpha at 193 N, level 3 = level 4 within 0.2 %', static_alpha_193(1), &
                     static_alpha_193(2), 0.002_dp)
    call check('static: alpha at 193 N grows from level 3 to 4 (the coarser mesh is stiffer)', &
               static_alpha_193(1) < static_alpha_193(2), exact_text(static_alpha_193(1))//' m, '// &
               exact_text(static_alpha_193(2))//' m')
  end subroutine convergence
end program test_contact_static
