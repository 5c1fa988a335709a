!> The size of a deck's run, known before it starts (the model is in
!> visco2d_budget): what `visco2d check` prints, the refusal of a run over
!> the memory limit (located at the MESH card, or the first ELEMENT card),
!> and the one-line note on stderr before a run estimated to be long.
module visco2d_estimate
  use, intrinsic :: iso_fortran_env, only: int64
  use visco2d_kinds, only: dp, kinematics_large, formulation_bbar
  use visco2d_error, only: error_t, set_error
  use visco2d_deck, only: deck_t, analysis_static, analysis_quasistatic, analysis_dynamic
  use visco2d_deck_types, only: solver_card_default, solver_card_cholmod
  use visco2d_material, only: has_memory, hyperelastic_foam, hyperelastic_mooney_rivlin
  use visco2d_mesh, only: side_nodes
  use visco2d_budget, only: run_size_t, run_size, time_limit, budget_static, budget_quasistatic, budget_dynamic, &
                            memory_limit, bytes_text, count_text, seconds_text, long_run_seconds
  implicit none
  private

  public :: run_size_t, estimate_run, check_run_size, check_run_time, estimate_line, long_run_note, print_estimate, size_before_work

  !> Contact iterations assumed for a STATIC run with a PLATE (one
  !> factorization each; the shipped static contact runs take 3 to 15).
  integer, parameter :: static_contact_iterations = 10
  !> Newton iterations assumed per load increment of a STATIC run with a
  !> PLASTIC material or KINEMATICS LARGE (one factorization each; measured
  !> 1 to 4, 3.5 on test/fuzz/seed_plastic_static.inp, on the plate or not;
  !> 3 and 3.45 on the finite-deformation cylinders of doc/finite.md).
  integer, parameter :: static_plastic_iterations = 4
  !> The cost of a DYNAMIC step with KINEMATICS LARGE against a small-strain
  !> one: 2 to 4 equilibrium iterations and an evaluation of the bodies at the
  !> step's end. Measured 3.2 on inputs/table1_large.inp at level 3 (every
  !> element neo-Hookean: the lean pass of visco2d_finite_force) and 10 on
  !> inputs/peach_foam_pad.inp (the foam's elements through the general
  !> element evaluation).
  integer, parameter :: dynamic_finite_lean = 4, dynamic_finite_general = 12

contains

  !> The estimated size of the deck's run (its mesh is built).
  function estimate_run(deck) result(estimate)
    type(deck_t), intent(in) :: deck
    type(run_size_t) :: estimate
    integer(int64) :: steps, terms, rows, contact
    integer :: analysis, columns, snapshots, written, probes, stages, k
    logical :: plate

    probes = 0
    if (allocated(deck%probes)) probes = size(deck%probes)
    stages = 0
    if (allocated(deck%stages)) stages = size(deck%stages)
    steps = 0
    do k = 1, stages
      steps = steps + int(deck%stages(k)%steps, int64)
    end do
    plate = deck%plate%line > 0
    terms = 0
    do k = 1, deck%mesh%nelem
      associate (material => deck%materials(max(deck%mesh%element_material(k), 1)))
      if (has_memory(material)) terms = terms + size(material%prony_rate)
      end associate
    end do
    contact = 0
    if (plate) contact = 2*lowest_boundary_nodes(deck)
    select case (deck%analysis)
    case (analysis_quasistatic)
      analysis = budget_quasistatic
      rows = steps + 1
      columns = 5 + 6*probes
      snapshots = 1                                   ! the initial one, at the second factorization
      written = 2                                     ! the initial and the final one
      contact = 0
    case (analysis_dynamic)
      analysis = budget_dynamic
      rows = steps/max(deck%output%every, 1) + 2
      columns = 14 + 10*probes
      if (plate) columns = columns + 9
      snapshots = 4                                   ! initial, final, the kept maxima
      if (allocated(deck%output%field_times)) snapshots = snapshots + size(deck%output%field_times)
      written = snapshots
    case default
      analysis = budget_static
      steps = 0
      rows = 1
      columns = 10 + 6*probes
      snapshots = 0                                   ! made after the factor is freed
      written = 1
      contact = 0
    end select
    estimate = run_size(analysis, int(deck%mesh%nnode, int64), int(deck%mesh%nelem, int64), &
                        int(deck%mesh%half_bandwidth, int64), steps, stages, terms, rows, columns, snapshots, contact, &
                        written_snapshots=written, &
                        sparse=deck%settings%solver == solver_card_default .or. &
                               deck%settings%solver == solver_card_cholmod)
    if (analysis == budget_static .and. (any(deck%materials%plastic) .or. &
                                         deck%settings%kinematics == kinematics_large)) then
      estimate%seconds = real(deck%settings%increments, dp)*static_plastic_iterations*estimate%seconds
    else if (analysis == budget_static .and. plate) then
      estimate%seconds = static_contact_iterations*estimate%seconds
    else if (analysis == budget_dynamic .and. deck%settings%kinematics == kinematics_large) then
      if (any(deck%materials%hyperelastic == hyperelastic_foam .or. deck%materials%hyperelastic == &
              hyperelastic_mooney_rivlin) .or. deck%settings%formulation == formulation_bbar) then
        estimate%seconds = dynamic_finite_general*estimate%seconds
      else
        estimate%seconds = dynamic_finite_lean*estimate%seconds
      end if
    end if
  end function estimate_run

  !> Boundary nodes in the lowest 2 % of the body's height: those a plate
  !> below the body may hold (the Table 1 impact, alpha = 1.1 mm, holds the
  !> nodes of the lowest 0.75 %). Each held node keeps up to 2 contact columns.
  !> With a PAD, the body is the mesh without the pad (nodes before
  !> pad%first_node): the body touches the pad's top.
  function lowest_boundary_nodes(deck) result(nodes)
    type(deck_t), intent(in) :: deck
    integer(int64) :: nodes
    logical, allocatable :: low(:)
    real(dp) :: bottom, reach
    integer :: k, a, b, body
    associate (mesh => deck%mesh)
    body = mesh%nnode
    if (deck%pad%first_node > 0) body = deck%pad%first_node - 1
    allocate(low(mesh%nnode))
    low = .false.
    bottom = minval(mesh%xy(2, :body))
    reach = bottom + 0.02_dp*(maxval(mesh%xy(2, :body)) - bottom)
    if (allocated(mesh%edge_element)) then
      do k = 1, size(mesh%edge_element)
        call side_nodes(mesh, mesh%edge_element(k), mesh%edge_side(k), a, b)
        if (a <= body .and. mesh%xy(2, a) <= reach) low(a) = .true.
        if (b <= body .and. mesh%xy(2, b) <= reach) low(b) = .true.
      end do
    end if
    nodes = count(low)
    end associate
  end function lowest_boundary_nodes

  !> Refuse a run whose estimated memory exceeds the limit: an error located
  !> at the card that defines the mesh, with the estimate by part.
  subroutine check_run_size(deck, size, error)
    type(deck_t), intent(in) :: deck
    type(run_size_t), intent(in) :: size
    type(error_t), allocatable, intent(inout) :: error
    real(dp) :: limit
    character(:), allocatable :: origin, hint
    logical :: raisable
    call memory_limit(limit, origin, raisable)
    if (size%total_bytes <= limit) return
    hint = ' (a coarser mesh'
    if (size%history_bytes > 0.25_dp*size%total_bytes) hint = hint//', a larger OUTPUT EVERY= or fewer steps'
    if (raisable) hint = hint//', or raise the limit with --max-memory SIZE or VISCO2D_MAX_MEMORY=SIZE'
    hint = hint//')'
    call set_error(error, 'this run would need about '//bytes_text(size%total_bytes)//' of memory ('// &
      parts_text(size)//'), more than '//origin//hint, file=deck%cards%file, line=deck%mesh%line, &
      column=deck%mesh%column, card=deck%mesh%card)
  end subroutine check_run_size

  !> Refuse a run whose rough time estimate exceeds the user's time limit
  !> (--max-time, VISCO2D_MAX_TIME; none by default): an error located at the
  !> first TIME card (the MESH card of a STATIC run), with the estimate.
  subroutine check_run_time(deck, size, error)
    type(deck_t), intent(in) :: deck
    type(run_size_t), intent(in) :: size
    type(error_t), allocatable, intent(inout) :: error
    real(dp) :: limit
    character(:), allocatable :: origin, what
    integer :: line
    call time_limit(limit, origin)
    if (limit <= 0.0_dp .or. size%seconds <= limit) return
    if (deck%analysis == analysis_static .and. (any(deck%materials%plastic) .or. &
                                                deck%settings%kinematics == kinematics_large)) then
      what = 'this run is estimated to take roughly '//seconds_text(size%seconds)//' ('// &
        count_text(int(deck%settings%increments, int64))//' load increments of '//count_text(size%equations)// &
        ' equations, half-bandwidth '//count_text(size%half_bandwidth)//'), more than the limit of '// &
        seconds_text(limit)//' set by '//origin//' (fewer INCREMENTS= or a coarser mesh; or raise the limit)'
    else
      what = 'this run is estimated to take roughly '//seconds_text(size%seconds)//' ('// &
        count_text(size%steps)//' steps of '//count_text(size%equations)//' equations, half-bandwidth '// &
        count_text(size%half_bandwidth)//'), more than the limit of '//seconds_text(limit)//' set by '// &
        origin//' (a larger DT, a shorter TEND or a coarser mesh; or raise the limit)'
    end if
    line = 0
    if (allocated(deck%stages)) then
      if (ubound(deck%stages, 1) >= 1) line = deck%stages(1)%line
    end if
    if (line > 0) then
      call set_error(error, what, file=deck%cards%file, line=line, card='TIME')
    else
      call set_error(error, what, file=deck%cards%file, line=deck%mesh%line, column=deck%mesh%column, &
                     card=deck%mesh%card)
    end if
  end subroutine check_run_time

  !> "stiffness and factor 1.2 GiB, elements 30 MiB, ...": the parts of an
  !> estimate (and those of the writing of results.h5 when it is the peak).
  function parts_text(size) result(text)
    type(run_size_t), intent(in) :: size
    character(:), allocatable :: text
    text = trim(merge('stiffness           ', 'stiffness and factor', size%factor_bytes > 0.0_dp))//' '// &
      bytes_text(size%band_bytes)//' for '//count_text(size%equations)// &
      ' equations of half-bandwidth '//count_text(size%half_bandwidth)//', elements '// &
      bytes_text(size%element_bytes)//', vectors and fields '//bytes_text(size%vector_bytes)
    if (size%history_bytes >= 1.0e6_dp) text = text//', history table '//bytes_text(size%history_bytes)// &
      ' ('//count_text(size%history_rows)//' rows)'
    if (size%factor_bytes > 0.0_dp) text = text//', sparse factor '//bytes_text(size%factor_bytes)
    if (size%contact_bytes >= 1.0e6_dp) text = text//', contact columns '//bytes_text(size%contact_bytes)
    if (size%write_bytes > size%solve_bytes) text = text//'; then, writing results.h5, '// &
      count_text(int(size%written_snapshots, int64))//' field snapshots '//bytes_text(size%snapshot_bytes)// &
      ' and the file''s image in memory '//bytes_text(size%image_bytes)
  end function parts_text

  !> Line k (1 to 4) of what `visco2d check` prints about the run's size:
  !> the memory against the limit, its parts, the output files and the rough
  !> run time.
  function estimate_line(size, k) result(line)
    type(run_size_t), intent(in) :: size
    integer, intent(in) :: k
    character(:), allocatable :: line
    real(dp) :: limit
    character(:), allocatable :: origin
    logical :: raisable
    select case (k)
    case (1)
      call memory_limit(limit, origin, raisable)
      line = '  memory          about '//bytes_text(size%total_bytes)//' (limit '//bytes_text(limit)//')'
    case (2)
      line = '                  stiffness '//bytes_text(size%band_bytes)//' ('// &
        count_text(int(size%band_copies, int64))//trim(merge(' band copy)  ', ' band copies)', &
        size%band_copies == 1))//', elements '//bytes_text(size%element_bytes)// &
        ', vectors '//bytes_text(size%vector_bytes)//', history '//bytes_text(size%history_bytes)
      if (size%factor_bytes > 0.0_dp) line = line//', sparse factor '//bytes_text(size%factor_bytes)
      if (size%contact_bytes > 0.0_dp) line = line//', contact '//bytes_text(size%contact_bytes)
      line = line//'; writing: snapshots '//bytes_text(size%snapshot_bytes)//' ('// &
        count_text(int(size%written_snapshots, int64))//'), results.h5 image '//bytes_text(size%image_bytes)
    case (3)
      line = '  output          about '//bytes_text(size%disk_bytes)//' on disk ('//count_text(size%history_rows)// &
             ' history rows)'
    case default
      line = '  run time        roughly '//seconds_text(size%seconds)
      if (size%steps > 0) line = line//' for at most '//count_text(size%steps)//' steps'
      line = line//' (one core; a rough model, within a factor of 2)'
    end select
  end function estimate_line

  !> The note printed on stderr before a run estimated to take longer than
  !> long_run_seconds ('' for a shorter one).
  function long_run_note(path, size) result(note)
    character(*), intent(in) :: path
    type(run_size_t), intent(in) :: size
    character(:), allocatable :: note
    note = ''
    if (size%seconds <= long_run_seconds) return
    note = 'visco2d: note: '//path//': a long run, roughly '//seconds_text(size%seconds)//' ('// &
      count_text(size%steps)//' steps of '//count_text(size%equations)//' equations, half-bandwidth '// &
      count_text(size%half_bandwidth)//'; about '//bytes_text(size%total_bytes)//' of memory'
    if (size%disk_bytes > 1.0e8_dp) note = note//', '//bytes_text(size%disk_bytes)//' of output ('// &
      count_text(size%history_rows)//' history rows)'
    note = note//')'
  end function long_run_note

  !> Print the estimate lines (visco2d check).
  subroutine print_estimate(size)
    type(run_size_t), intent(in) :: size
    integer :: k
    do k = 1, 4
      print '(a)', estimate_line(size, k)
    end do
  end subroutine print_estimate

  !> Before a run: refuse it if it would need more memory than the limit, and
  !> announce it on stderr if it is estimated to be long.
  subroutine size_before_work(path, deck, error)
    character(*), intent(in) :: path
    type(deck_t), intent(in) :: deck
    type(error_t), allocatable, intent(inout) :: error
    type(run_size_t) :: size
    character(:), allocatable :: note
    size = estimate_run(deck)
    call check_run_size(deck, size, error)
    if (allocated(error)) return
    call check_run_time(deck, size, error)
    if (allocated(error)) return
    note = long_run_note(path, size)
    if (len(note) > 0) then
      write(0, '(a)') note
      flush(0)
    end if
  end subroutine size_before_work
end module visco2d_estimate
