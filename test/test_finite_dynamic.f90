!> ANALYSIS DYNAMIC with KINEMATICS LARGE (visco2d_time_step's finite step,
!> visco2d_finite_force's lean pass):
!>  1. The lean pass equals the general evaluation (element_response through
!>     finite_assemble) to round-off: force, stresses, energy and the
!>     logarithmic strains, on an axisymmetric sphere, a plane-strain
!>     block and a sphere on a HYPERFOAM pad (its elements left to
!>     element_response) at a random finite displacement (force and stresses also at a
!>     displacement 1e-9 times smaller, where they keep their digits).
program test_finite_dynamic
  use visco2d_kinds, only: dp
  use visco2d_error, only: error_t, error_text
  use visco2d_testing, only: check, check_close, test_summary, write_deck
  use visco2d_test_decks, only: deck_line_length
  use visco2d_deck, only: deck_t, read_deck
  use visco2d_element, only: gauss_count
  use visco2d_assembly, only: node_dof
  use visco2d_finite_assembly, only: finite_assemble
  use visco2d_finite_force, only: finite_reference_t, finite_reference_create, lean_forces, gradient_strains
  implicit none

  character(*), parameter :: folder = 'build/test_finite_dynamic'

  call execute_command_line('rm -rf '//folder//' && mkdir -p '//folder)
  call lean_pass('sphere', [character(deck_line_length) :: 'TITLE lean pass, sphere', 'ANALYSIS DYNAMIC', &
    'KINEMATICS LARGE', 'MATERIAL flesh NEOHOOKE E=5e6 NU=0.45 RHO=950', 'MESH SPHERE R=0.03 LEVEL=1', &
    'TIME DT=1e-5 TEND=1e-5', 'END'], 0.0003_dp)
  call lean_pass('block', [character(deck_line_length) :: 'TITLE lean pass, plane strain', 'ANALYSIS DYNAMIC', &
    'GEOMETRY PLANESTRAIN', 'KINEMATICS LARGE', 'MATERIAL flesh ELASTIC E=5e6 NU=0.3 RHO=950', &
    'MESH RECT R0=0 R1=0.01 Z0=0 Z1=0.02 NR=3 NZ=5', 'TIME DT=1e-5 TEND=1e-5', 'END'], 0.001_dp)
  call lean_pass('foam_pad', [character(deck_line_length) :: 'TITLE lean pass, neo-Hookean sphere on a foam pad', &
    'ANALYSIS DYNAMIC', 'KINEMATICS LARGE', 'MATERIAL flesh NEOHOOKE E=5e6 NU=0.35 RHO=950', &
    'MATERIAL foam HYPERFOAM RHO=100', 'OGDEN MU=0.74e6 ALPHA=12 NU=0', 'OGDEN MU=0.01e6 ALPHA=-2 NU=0.1', &
    'MESH SPHERE R=0.03 LEVEL=1 MAT=flesh', 'PLATE Z=0 SLIP', 'PAD THICKNESS=0.01 MAT=foam', &
    'TIME DT=1e-5 TEND=1e-5', 'END'], 0.0003_dp)
  call test_summary('test_finite_dynamic')

contains

  !> Part 1 on the deck's mesh at a random displacement of amplitude `size`
  !> (strains of order size / element size, some 10-30 %), and at a tiny one (1e-9 of it).
  subroutine lean_pass(name, lines, amplitude)
    character(*), intent(in) :: name, lines(:)
    real(dp), intent(in) :: amplitude
    type(deck_t) :: deck
    type(error_t), allocatable :: error
    type(finite_reference_t) :: reference
    real(dp), allocatable :: u(:), force(:), stress(:, :, :), strain(:, :, :), lean_force(:), lean_stress(:, :, :), &
                             lean_strain(:, :, :), gradient(:, :, :)
    real(dp) :: energy, lean_energy, scale
    integer :: inverted, lean_inverted, k, node
    call write_deck(folder//'/'//name//'.inp', lines)
    call read_deck(folder//'/'//name//'.inp', deck, error)
    if (allocated(error)) then
      call check(name//'_deck', .false., error_text(error))
      return
    end if
    reference = finite_reference_create(deck%mesh, deck%materials, deck%settings)
    if (name == 'foam_pad') then                 ! the foam's elements go through element_response
      call check(name//'_mixed', any(reference%lean) .and. .not. all(reference%lean))
    else
      call check(name//'_lean', all(reference%lean))
    end if
    allocate(u(2*deck%mesh%nnode), force(2*deck%mesh%nnode), lean_force(2*deck%mesh%nnode))
    allocate(stress(4, gauss_count, deck%mesh%nelem), strain(4, gauss_count, deck%mesh%nelem), &
             lean_stress(4, gauss_count, deck%mesh%nelem), lean_strain(4, gauss_count, deck%mesh%nelem))
    allocate(gradient(5, gauss_count, deck%mesh%nelem))
    do k = 1, 2
      call random_seed()
      call random_number(u)
      u = (u - 0.5_dp)*amplitude*merge(1.0_dp, 1.0e-9_dp, k == 1)
      do node = 1, deck%mesh%nnode                      ! the axis stays on the axis
        if (deck%mesh%xy(1, node) == 0.0_dp) u(node_dof(deck%mesh, node, 1)) = 0.0_dp
      end do
      call finite_assemble(deck%mesh, deck%materials, deck%settings, u, force, stress, strain, energy, inverted)
      call lean_forces(reference, deck%mesh, deck%materials, deck%settings, u, lean_force, lean_stress, lean_energy, &
                       lean_inverted, gradient, lean_strain)
      call check(name//'_valid_'//merge('large', 'small', k == 1), inverted == 0 .and. lean_inverted == 0)
      if (inverted /= 0 .or. lean_inverted /= 0) cycle
      call gradient_strains(reference, gradient, lean_strain)
      scale = maxval(abs(force))
      call check_close(name//'_force_'//merge('large', 'small', k == 1), maxval(abs(lean_force - force))/scale, &
                       0.0_dp, 0.0_dp, 1.0e-12_dp)
      scale = maxval(abs(stress))
      call check_close(name//'_stress_'//merge('large', 'small', k == 1), maxval(abs(lean_stress - stress))/scale, &
                       0.0_dp, 0.0_dp, 1.0e-12_dp)
      ! W and the general evaluation's ln V are O(strain^2) and O(strain) differences of O(1) numbers (the
      ! isochoric W from I1bar - 3, ln V from the eigenvalues of F F^T): at the tiny displacement they keep
      ! only 1e-16 / strain of their digits. There the lean ln V (from b - I) is checked against sym(H),
      ! which it equals to O(H^2): relative to |H| within 10 |H| (|H| ~ 1e-10 here; the round-off of
      ! a log(1 + x) evaluation would be 1e-16 / |H| = 1e-6 of it).
      if (k == 2) then
        do node = 1, deck%mesh%nelem                   ! the gradients are the lean elements' only
          if (reference%lean(node)) cycle
          gradient(:, :, node) = 0.0_dp
          lean_strain(:, :, node) = 0.0_dp
        end do
        scale = maxval(abs(gradient))
        call check_close(name//'_strain_small_vs_sym_H', maxval(abs([lean_strain(1, :, :) - gradient(1, :, :), &
          lean_strain(2, :, :) - gradient(4, :, :), lean_strain(3, :, :) - gradient(5, :, :), &
          lean_strain(4, :, :) - gradient(2, :, :) - gradient(3, :, :)]))/scale, 0.0_dp, 0.0_dp, 10.0_dp*scale)
        cycle
      end if
      call check_close(name//'_energy_'//merge('large', 'small', k == 1), lean_energy, energy, 1.0e-12_dp)
      scale = maxval(abs(strain))
      call check_close(name//'_strain_'//merge('large', 'small', k == 1), maxval(abs(lean_strain - strain))/scale, &
                       0.0_dp, 0.0_dp, 1.0e-12_dp)
    end do
  end subroutine lean_pass

end program test_finite_dynamic
