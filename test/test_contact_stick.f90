!> Static contact with STICK (a bonded, no-slip plate) and the load path of
!> solve_static_contact, checked against exact statements and the known
!> half-space result.
!>
!> 1. The Table-1 sphere (MESH SPHERE levels 3, 4) pressed on PLATE Z=0 STICK
!>    and SLIP by GRAVITY G = F/M, F = 50, 100, 200 N (STICK did not settle
!>    at >= 50 N on level 3 and >= 100 N on level 4 before the path was
!>    followed). Each run settles; the final state is admissible, checked here
!>    from the written displacements alone: the nodes on the plate, held where
!>    they are, all push, and no other node is through the plate. STICK is
!>    stiffer than SLIP (smaller approach at the same force), and no more
!>    nodes touch. Both are printed against Hertz.
!> 2. The bonded/frictionless stiffness of one contact patch. With the patch
!>    fixed, holding u_r as well can only stiffen (more constraints: exact).
!>    On a half-space, a rigid flat circular punch bonded to the surface has
!>    stiffness 4 G a ln(3 - 4 nu)/(1 - 2 nu) (Mossakovskii; Ufliand), the
!>    frictionless one 4 G a/(1 - nu): the ratio ln(3 - 4 nu)(1 - nu)/(1 - 2 nu)
!>    is 1.0986 at nu = 0, 1.0468 at nu = 0.219, 1.0028 at nu = 0.45 and 1 at
!>    nu = 1/2. An incremental no-slip contact stiffens by exactly that
!>    bonded increment, so this is the "known small amount". The sphere's
!>    patch (B-bar elements, the same nodes on every level: those within
!>    1.9 mm of the pole; the default contact grid) converges with the mesh,
!>    to the limit the standard element converges to, near that value.
!> 3. Regression decks: a flat block that the one-shot STICK iteration could
!>    not settle; a block in which a stuck node freed at zero force would go
!>    through the plate and so slides; a disc resting flat on the plate
!>    (every bottom node at zero gap and zero force at the start, lifted at
!>    its rim), where changing every violating node at once comes back to an
!>    earlier set and the least-index rule ends it.
program test_contact_stick
  use visco2d_kinds, only: dp, pi
  use visco2d_error, only: error_t, error_text
  use visco2d_deck, only: deck_t, read_deck
  use visco2d_static, only: static_solution_t, solve_static
  use visco2d_contact, only: contact_t, contact_create, contact_gap
  use visco2d_static_contact, only: solve_static_contact
  use visco2d_assembly, only: node_dof, band_vector, lumped_mass
  use visco2d_record, only: record_t
  use visco2d_expect, only: summary_value
  use visco2d_strings, only: integer_text
  use visco2d_testing, only: check, check_close, test_summary, write_deck, summary_real, exact_text
  use visco2d_test_decks, only: pressed_sphere
  implicit none

  character(*), parameter :: folder = 'build/test-tmp/test_contact_stick'
  real(dp), parameter :: young = 18.11e6_dp, poisson = 0.219_dp, radius = 0.0366_dp
  real(dp), parameter :: modulus = young/(1.0_dp - poisson**2)
  real(dp), parameter :: loads(3) = [50.0_dp, 100.0_dp, 200.0_dp]
  !> Section 2's patch: the nodes with r up to this (m), the same on levels 2-6.
  real(dp), parameter :: patch_radius = 1.9e-3_dp
  real(dp), parameter :: absent = -huge(1.0_dp)   ! an absent summary value: nint and the table stay NaN-free
  integer :: level, k

  call execute_command_line('mkdir -p '//folder)

  print '(a)', ''
  print '(a)', '## 1. Static indentation of the Table-1 sphere, STICK and SLIP (GRAVITY G = F/M)'
  print '(a)', ''
  print '(a)', '| level | F (N) | alpha SLIP (mm) | alpha STICK (mm) | alpha_H (mm) | SLIP/H - 1 | STICK/H - 1 | '// &
               'STICK/SLIP - 1 | nodes SLIP | nodes STICK | r_out SLIP (mm) | r_out STICK (mm) | a_H (mm) | '// &
               'q SLIP (MPa) | q STICK (MPa) | q_H (MPa) |'
  print '(a)', '|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|'
  do level = 3, 4
    do k = 1, size(loads)
      call stick_and_slip(level, loads(k))
    end do
  end do

  print '(a)', ''
  print '(a)', '## 2. Bonded / frictionless stiffness of one contact patch (nodes within 1.9 mm of the pole)'
  print '(a)', ''
  print '(a)', '| formulation | level | nu | patch nodes | k_bonded/k_frictionless | half-space '// &
               'ln(3-4nu)(1-nu)/(1-2nu) | share of the half-space excess |'
  print '(a)', '|---|---|---|---|---|---|---|'
  call patch_ratios()

  call regressions()
  call test_summary('test_contact_stick')

contains

  !> The sphere deck at `level` pressed by `force` (N) with PLATE ... `mode`.
  function sphere_deck(level, force, mode, name) result(file)
    integer, intent(in) :: level
    real(dp), intent(in) :: force
    character(*), intent(in) :: mode, name
    character(:), allocatable :: file
    type(deck_t) :: deck
    type(error_t), allocatable :: error
    real(dp), allocatable :: weight(:)
    real(dp) :: mass
    character(*), parameter :: title = 'Static indentation of the Table-1 sphere'
    ! The mesh's own mass (2 pi rho int dV), so that the plate carries F exactly.
    file = folder//'/'//name//'.inp'
    call write_deck(file, pressed_sphere(title, level, mode, 1.0_dp))
    call read_deck(file, deck, error)
    if (allocated(error)) then
      call check(name//': reads', .false., error_text(error))
      return
    end if
    weight = lumped_mass(deck%mesh, deck%settings, deck%materials, volume=.true.)
    mass = 2.0_dp*pi*756.85_dp*sum(weight(2::2))
    call write_deck(file, pressed_sphere(title, level, mode, force/mass))
  end function sphere_deck

  !> Solve a static contact deck; check that it settles with an admissible state.
  subroutine press(file, tag, record, nodes, r_out, ok)
    character(*), intent(in) :: file, tag
    type(record_t), intent(out) :: record
    integer, intent(out) :: nodes
    real(dp), intent(out) :: r_out
    logical, intent(out) :: ok
    type(deck_t) :: deck
    type(error_t), allocatable :: error
    nodes = 0
    r_out = 0.0_dp
    call read_deck(file, deck, error)
    if (.not. allocated(error)) call solve_static_contact(deck, record, error)
    ok = .not. allocated(error)
    if (.not. ok) then
      call check(tag//': settles', .false., error_text(error))
      return
    end if
    call check(tag//': settles', .true.)
    call admissible(deck, record, tag, nodes, r_out)
  end subroutine press

  !> From the written final displacements alone: the nodes on the plate (gap
  !> within the tolerance) are the summary's contact_nodes; held where they
  !> are (u_z and u_r: a stuck node's u_r is where it touched, a sliding
  !> node's u_r is the equilibrium one, so holding it changes nothing), the
  !> state solves again to the same displacements, every one of them pushes
  !> (z reaction >= -1e-9 of the largest), and no other node is through the plate.
  subroutine admissible(deck, record, tag, nodes, r_out)
    type(deck_t), intent(in) :: deck
    type(record_t), intent(in) :: record
    character(*), intent(in) :: tag
    integer, intent(out) :: nodes
    real(dp), intent(out) :: r_out
    type(contact_t) :: contact
    type(static_solution_t) :: solution
    type(error_t), allocatable :: error
    real(dp), allocatable :: u(:), reaction(:), values(:)
    logical, allocatable :: held(:)
    real(dp) :: gap, deepest, pull, largest, change
    integer :: i, node
    associate (mesh => deck%mesh)
    u = band_vector(mesh, record%snapshots(size(record%snapshots))%displacement)
    call contact_create(deck, contact)
    allocate(held(2*mesh%nnode))
    held = .false.
    deepest = 0.0_dp
    r_out = 0.0_dp
    do i = 1, size(contact%candidates)
      node = contact%candidates(i)
      gap = contact_gap(deck, contact, u, node)
      contact%active(node) = abs(gap) <= contact%tolerance
      if (contact%active(node)) then
        held(node_dof(mesh, node, 1):node_dof(mesh, node, 2)) = .true.
        r_out = max(r_out, mesh%xy(1, node))
      else
        deepest = min(deepest, gap)
      end if
    end do
    nodes = count(contact%active)
    call check(tag//': the nodes on the plate are the contact_nodes', &
               nodes == nint(summary_real(record, 'contact_nodes', absent)), &
               integer_text(nodes)//' vs '//summary_value(record, 'contact_nodes'))
    call check(tag//': no free node through the plate', deepest >= -contact%tolerance, exact_text(deepest))
    values = merge(u, 0.0_dp, held)
    call solve_static(deck%mesh, deck%materials, deck%settings, deck%loads, deck%source, solution, error, held, values)
    if (allocated(error)) then
      call check(tag//': the final set solves again', .false., error_text(error))
      return
    end if
    reaction = band_vector(mesh, solution%reaction)
    change = maxval(abs(band_vector(mesh, solution%displacement) - u))/maxval(abs(u))
    ! Round-off of a banded solve and of the snapshot: 1e-9 relative.
    call check(tag//': held where they are, the state solves to itself', change <= 1.0e-9_dp, exact_text(change))
    largest = 0.0_dp
    pull = 0.0_dp
    do i = 1, size(contact%candidates)
      node = contact%candidates(i)
      if (.not. contact%active(node)) cycle
      largest = max(largest, abs(reaction(node_dof(mesh, node, 2))))
      pull = min(pull, reaction(node_dof(mesh, node, 2)))
    end do
    call check(tag//': every node on the plate pushes', pull >= -1.0e-9_dp*largest, exact_text(pull/max(largest, &
               tiny(1.0_dp))))
    end associate
  end subroutine admissible

  !> Section 1 at one level and load.
  subroutine stick_and_slip(level, force)
    integer, intent(in) :: level
    real(dp), intent(in) :: force
    type(record_t) :: slip, stick
    character(:), allocatable :: tag
    real(dp) :: alpha_slip, alpha_stick, alpha_h, a_h, q_h, r_slip, r_stick
    integer :: n_slip, n_stick
    logical :: ok_slip, ok_stick
    tag = 'level '//integer_text(level)//' F = '//integer_text(nint(force))//' N'
    call press(sphere_deck(level, force, 'SLIP', 'slip_'//integer_text(level)//'_'//integer_text(nint(force))), tag//' SLIP',&
      slip, &
               n_slip, r_slip, ok_slip)
    call press(sphere_deck(level, force, 'STICK', 'stick_'//integer_text(level)//'_'//integer_text(nint(force))), tag//' STICK', &
               stick, n_stick, r_stick, ok_stick)
    if (.not. (ok_slip .and. ok_stick)) return
    ! The plate carries the whole weight M G = F (the summary's 10 digits).
    call check_close(tag//' STICK: force_N = F', summary_real(stick, 'force_N', absent), force, 1.0e-9_dp)
    call check(tag//' STICK: no node had to slide', summary_value(stick, 'contact_sliding_nodes') == '0', &
               summary_value(stick, 'contact_sliding_nodes'))
    alpha_slip = summary_real(slip, 'alpha_mm', absent)
    alpha_stick = summary_real(stick, 'alpha_mm', absent)
    call check(tag//': STICK approaches less than SLIP (bonded is stiffer)', alpha_stick < alpha_slip, &
               exact_text(alpha_stick)//' vs '//exact_text(alpha_slip))
    call check(tag//': STICK touches with no more nodes than SLIP', n_stick <= n_slip)
    a_h = (3.0_dp*force*radius/(4.0_dp*modulus))**(1.0_dp/3.0_dp)
    alpha_h = a_h**2/radius
    q_h = 3.0_dp*force/(2.0_dp*pi*a_h**2)
    print '(a, i0, a, f5.0, a, 3(f9.5, a), 3(sp, f8.4, ss, a), 2(i3, a), 3(f7.3, a), 3(f7.4, a))', '| ', level, ' | ', &
      force, ' | ', alpha_slip, ' | ', alpha_stick, ' | ', 1.0e3_dp*alpha_h, ' | ', &
      alpha_slip/(1.0e3_dp*alpha_h) - 1.0_dp, ' | ', alpha_stick/(1.0e3_dp*alpha_h) - 1.0_dp, ' | ', &
      alpha_stick/alpha_slip - 1.0_dp, ' | ', n_slip, ' | ', n_stick, ' | ', 1.0e3_dp*r_slip, ' | ', &
      1.0e3_dp*r_stick, ' | ', 1.0e3_dp*a_h, ' | ', summary_real(slip, 'q_MPa', absent), ' | ', &
      summary_real(stick, 'q_MPa', absent), ' | ', 1.0e-6_dp*q_h, ' |'
  end subroutine stick_and_slip

  !> Section 2.
  subroutine patch_ratios()
    real(dp), parameter :: nus(3) = [0.0_dp, 0.219_dp, 0.45_dp]
    real(dp) :: ratio(3, 2:4), standard(2:4), gap(2:4), exact
    integer :: i, level
    do i = 1, size(nus)
      exact = log(3.0_dp - 4.0_dp*nus(i))*(1.0_dp - nus(i))/(1.0_dp - 2.0_dp*nus(i))
      do level = 2, 4
        ratio(i, level) = patch_ratio(level, nus(i), 'BBAR')
        call check('patch level '//integer_text(level)//' nu = '//exact_text(nus(i))//': bonded is stiffer (exact)', &
                   ratio(i, level) > 1.0_dp, exact_text(ratio(i, level)))
      end do
      ! The patch is the same nodes on every level, r <= 1.885 mm (a/R =
      ! 0.052): the level-2 grid's first five surface nodes, where the next
      ! node lies at 2.685 mm (level 2), 2.262 (3), 2.068 (4), 1.975 (5),
      ! 1.929 (6). (It was the nodes within 2.5 mm, whose edge moved with the
      ! level: 1.885, 2.262, 2.467, 2.467 mm on levels 2-5 here, 1.369,
      ! 2.119, 2.119, 2.314 mm on the GRADE=2.5 grid, so the level changes
      ! mixed the patch's size with the mesh.)
      ! Convergence, measured offline on levels 2-6 (B-bar; standard):
      ! nu = 0: 1.10435, 1.10540, 1.10593, 1.10610, 1.10610; 1.09856,
      ! 1.10279, 1.10468, 1.10547, 1.10577. nu = 0.219: 1.04844, 1.04812,
      ! 1.04794, 1.04777, 1.04761; 1.04311, 1.04578, 1.04686, 1.04724,
      ! 1.04734. The two elements tend to one limit, 1.1061 and about 1.0474,
      ! but at nu = 0.219 B-bar only as h^0.5 (its distance from 1.0474 falls
      ! by 0.59-0.76 per level; the standard element's changes by 0.26-0.40),
      ! so "the level 3 -> 4 change at most half the 2 -> 3 change" (p >= 1,
      ! as for alpha_m in test_contact_dynamic) is not a property of B-bar
      ! here: with the 2.5 mm patch it read 1.04844, 1.04797, 1.04760 (0.78),
      ! with this one 0.56 (and 0.94 from level 4 to 5). Checked instead, for
      ! each: the gap between the two elements shrinks with every level
      ! (measured 5.79e-3, 2.61e-3, 1.25e-3 at nu = 0; 5.33e-3, 2.34e-3,
      ! 1.08e-3 at nu = 0.219), and B-bar's own changes shrink (1.05e-3 then
      ! 5.3e-4; 3.2e-4 then 1.8e-4).
      ! Its value: the limit lies above the half-space excess at nu = 0 by
      ! 7.6 % of it, a finite-patch effect (it grows with the patch: B-bar
      ! at level 6 gives 1.076 of the excess at 1.885 mm, 1.102 at 2.685 mm),
      ! by about 1 % at nu = 0.219; level 4 must hold 70-110 % of it
      ! (measured 1.074 and 1.023; on the GRADE=2.5 grid with the 2.5 mm
      ! patch 1.079 and 1.027, on the legacy grid 0.93 and 0.78).
      if (nus(i) < 0.3_dp) then
        do level = 2, 4
          standard(level) = patch_ratio(level, nus(i), 'STANDARD')
        end do
        gap = abs(ratio(i, :) - standard)
        call check('patch nu = '//exact_text(nus(i))//': converges (B-bar and standard gap shrinks per level, '// &
                   'B-bar''s changes shrink)', gap(3) < gap(2) .and. gap(4) < gap(3) .and. &
                   abs(ratio(i, 4) - ratio(i, 3)) < abs(ratio(i, 3) - ratio(i, 2)), &
                   'B-bar '//exact_text(ratio(i, 2))//', '//exact_text(ratio(i, 3))//', '// &
                   exact_text(ratio(i, 4))//'; gaps '//exact_text(gap(2))//', '//exact_text(gap(3))//', '// &
                   exact_text(gap(4)))
        call check('patch nu = '//exact_text(nus(i))//': level 4 has 70-110 % of the half-space excess', &
                   (ratio(i, 4) - 1.0_dp)/(exact - 1.0_dp) > 0.7_dp .and. &
                   (ratio(i, 4) - 1.0_dp)/(exact - 1.0_dp) < 1.1_dp, &
                   exact_text((ratio(i, 4) - 1.0_dp)/(exact - 1.0_dp)))
      else
        ! Near incompressibility the difference vanishes (0.0028 on a half-space;
        ! B-bar, level 4: 0.0016; the standard element, printed, 0.0014 on the
        ! contact grid, where on the legacy grid it locked under the extra
        ! constraints and showed 0.0127).
        call check('patch nu = 0.45: bonded and frictionless within 0.5 % (B-bar, level 4)', &
                   ratio(i, 4) - 1.0_dp < 0.005_dp, exact_text(ratio(i, 4)))
        standard(4) = patch_ratio(4, nus(i), 'STANDARD')
      end if
    end do
  end subroutine patch_ratios

  !> k_bonded / k_frictionless of the patch of nodes within patch_radius of the pole
  !> held on the plate (u_z, and u_r when bonded), the sphere loaded by gravity:
  !> k = M g / (d alpha), alpha the volume-mean u_z.
  real(dp) function patch_ratio(level, nu, formulation) result(ratio)
    integer, intent(in) :: level
    real(dp), intent(in) :: nu
    character(*), intent(in) :: formulation
    type(deck_t) :: deck
    type(error_t), allocatable :: error
    type(contact_t) :: contact
    type(static_solution_t) :: solution
    real(dp), allocatable :: zero(:), weight(:), u(:)
    logical, allocatable :: held(:)
    real(dp) :: compliance(2)
    integer :: i, node, bonded, nodes
    character(:), allocatable :: file
    file = folder//'/patch.inp'
    call write_deck(file, [character(len=80) :: 'TITLE patch', 'ANALYSIS STATIC', 'GEOMETRY AXISYMMETRIC', &
      'FORMULATION '//formulation, 'MATERIAL m ELASTIC E=18.11e6 NU='//exact_text(nu)//' RHO=756.85', &
      'MESH SPHERE R=0.0366 LEVEL='//integer_text(level), 'PLATE Z=0 STICK', 'GRAVITY G=100', 'END'])
    ratio = 0.0_dp
    call read_deck(file, deck, error)
    if (allocated(error)) then
      call check('patch deck reads', .false., error_text(error))
      return
    end if
    call contact_create(deck, contact)
    allocate(zero(2*deck%mesh%nnode), held(2*deck%mesh%nnode))
    zero = 0.0_dp
    weight = lumped_mass(deck%mesh, deck%settings, deck%materials, volume=.true.)
    do bonded = 1, 2
      held = .false.
      nodes = 0
      do i = 1, size(contact%candidates)
        node = contact%candidates(i)
        if (deck%mesh%xy(1, node) > patch_radius .or. deck%mesh%xy(2, node) > 0.5_dp*radius) cycle
        held(node_dof(deck%mesh, node, 2)) = .true.
        if (bonded == 1) held(node_dof(deck%mesh, node, 1)) = .true.
        nodes = nodes + 1
      end do
      call solve_static(deck%mesh, deck%materials, deck%settings, deck%loads, deck%source, solution, error, held, zero)
      if (allocated(error)) then
        call check('patch solves', .false., error_text(error))
        return
      end if
      u = band_vector(deck%mesh, solution%displacement)
      compliance(bonded) = -dot_product(weight(2::2), u(2::2))/sum(weight(2::2))
    end do
    ratio = compliance(2)/compliance(1)
    associate (exact => log(3.0_dp - 4.0_dp*nu)*(1.0_dp - nu)/(1.0_dp - 2.0_dp*nu))
    print '(a, i0, a, f6.3, a, i0, a, 2(f8.5, a), f7.3, a)', '| '//formulation//' | ', level, ' | ', nu, ' | ', &
      nodes, ' | ', ratio, ' | ', exact, ' | ', (ratio - 1.0_dp)/(exact - 1.0_dp), ' |'
    end associate
  end function patch_ratio

  !> Section 3.
  subroutine regressions()
    type(record_t) :: record
    integer :: nodes
    real(dp) :: r_out
    logical :: ok
    character(:), allocatable :: file
    print '(a)', ''
    print '(a)', '## 3. Regression decks'
    print '(a)', ''
    ! A flat block with a pressure and three point forces: the one-shot STICK
    ! iteration ran out of its 100 iterations.
    file = folder//'/block_stick.inp'
    call write_deck(file, [character(len=80) :: 'TITLE block', 'ANALYSIS STATIC', 'GEOMETRY AXISYMMETRIC', &
      'MATERIAL m ELASTIC E=5.0e6 NU=0.254', 'MESH RECT R0=0 R1=0.013 Z0=0 Z1=0.009 NR=6 NZ=5', 'PLATE Z=0 STICK', &
      'PRESSURE TOP P=6.661e+04', 'FORCE 33 FR=-19.154 FZ=-5.889', 'FORCE 16 FR=-25.322 FZ=-3.443', &
      'FORCE 4 FR=48.979 FZ=3.555', 'END'])
    call press(file, 'block STICK (the one-shot iteration did not settle)', record, nodes, r_out, ok)
    ! A block whose bottom corner node, stuck, pulls at zero force and, freed,
    ! would go through the plate: it slides.
    file = folder//'/block_slide.inp'
    call write_deck(file, [character(len=80) :: 'TITLE block', 'ANALYSIS STATIC', 'GEOMETRY AXISYMMETRIC', &
      'MATERIAL m ELASTIC E=5.0e6 NU=0.120', 'MESH RECT R0=0 R1=0.034 Z0=0 Z1=0.008 NR=8 NZ=3', 'PLATE Z=0 STICK', &
      'PRESSURE TOP P=9.361e+03', 'FORCE 25 FR=-14.152 FZ=-2.780', 'FORCE 29 FR=-38.320 FZ=-7.554', 'END'])
    call press(file, 'block STICK with a sliding node', record, nodes, r_out, ok)
    if (ok) call check('block STICK with a sliding node: contact_sliding_nodes = 1', &
                       summary_value(record, 'contact_sliding_nodes') == '1', summary_value(record, 'contact_sliding_nodes'))
    ! A disc flat on the plate, pressed down at its rim: every bottom node at
    ! zero gap and force at lambda = 0, most of them lift.
    file = folder//'/disc_slip.inp'
    call write_deck(file, [character(len=80) :: 'TITLE disc', 'ANALYSIS STATIC', 'GEOMETRY AXISYMMETRIC', &
      'MATERIAL m ELASTIC E=5.0e6 NU=0.3', 'MESH RECT R0=0 R1=0.05 Z0=0 Z1=0.005 NR=20 NZ=4', 'PLATE Z=0 SLIP', &
      'FORCE 105 FZ=-10', 'END'])
    call press(file, 'disc SLIP lifted at a degenerate start', record, nodes, r_out, ok)
    if (ok) call check('disc SLIP: it rests on its rim (2 nodes)', nodes == 2, integer_text(nodes))
    call lifted_off()
    call overflowed()
  end subroutine regressions

  !> E = 1e308: the stiffness overflows. Refused (when the deck is read, or
  !> by the solver: "not a finite number"), never "did not settle" nor NaN results.
  subroutine overflowed()
    character(:), allocatable :: text
    logical :: refused
    call expect_refused('E = 1e308', folder//'/overflow.inp', [character(len=80) :: 'TITLE overflow', &
      'ANALYSIS STATIC', 'GEOMETRY AXISYMMETRIC', 'MATERIAL m ELASTIC E=1e308 NU=0.219 RHO=756.85', &
      'MESH SPHERE R=0.0366 LEVEL=2', 'PLATE Z=0 STICK', 'GRAVITY G=300', 'END'], refused, text)
    if (refused) call check('E = 1e308: not reported as a contact set that did not settle', &
                            index(text, 'did not settle') == 0, text)
  end subroutine overflowed

  !> A block pulled off the plate: nothing holds it once every bottom node is
  !> freed at lambda = 0. The singular stiffness is reported at the PLATE card
  !> (line 6), with the advice about a body that only rests on the plate.
  subroutine lifted_off()
    character(:), allocatable :: file, text
    logical :: refused
    file = folder//'/lifted.inp'
    call expect_refused('lifted block', file, [character(len=80) :: 'TITLE lifted', 'ANALYSIS STATIC', &
      'GEOMETRY PLANESTRAIN', 'MATERIAL m ELASTIC E=5.0e6 NU=0.3', 'MESH RECT R0=0 R1=0.02 Z0=0 Z1=0.01 NR=4 NZ=2', &
      'PLATE Z=0 SLIP', 'FORCE 15 FZ=5', 'FIX AXIS R', 'END'], refused, text)
    if (.not. refused) return
    call check('lifted block: located at the PLATE card', index(text, file//':6: PLATE: ') == 1, text)
    call check('lifted block: says why', index(text, '0 node(s) on the plate') > 0 .and. &
               index(text, 'only rests on the plate') > 0, text)
  end subroutine lifted_off

  !> The deck, written to `file`, is read and solved with static contact: it
  !> must be refused (check `<name>: refused`). The error's text is printed
  !> and returned ('' if the deck was not refused).
  subroutine expect_refused(name, file, deck_lines, refused, text)
    character(*), intent(in) :: name, file, deck_lines(:)
    logical, intent(out) :: refused
    character(:), allocatable, intent(out) :: text
    type(deck_t) :: deck
    type(record_t) :: record
    type(error_t), allocatable :: error
    call write_deck(file, deck_lines)
    call read_deck(file, deck, error)
    if (.not. allocated(error)) call solve_static_contact(deck, record, error)
    refused = allocated(error)
    call check(name//': refused', refused)
    text = ''
    if (.not. refused) return
    text = error_text(error)
    print '(a)', text
  end subroutine expect_refused
end program test_contact_stick
