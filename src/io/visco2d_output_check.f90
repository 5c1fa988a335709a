!> The last check before a case folder is written: no NaN or Infinity may
!> reach an output. Every number the outputs hold is looked at: the summary
!> values, every history cell, every snapshot field and time (results.h5),
!> and the deck's numbers that listing.txt and results.h5 echo (materials
!> with their derived moduli, time stages, curves, loads, node coordinates).
!> The first non-finite one found is reported as a located error that says
!> where it is and which analysis (or which card) it came from.
module visco2d_output_check
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_is_nan
  use visco2d_kinds, only: dp
  use visco2d_error, only: error_t, set_error
  use visco2d_strings, only: integer_text, table_real
  use visco2d_deck, only: deck_t, analysis_name, analysis_dynamic, initial_velocity
  use visco2d_record, only: record_t, snapshot_t
  implicit none
  private

  public :: check_finite_outputs, non_finite_text, finite_text

  !> Summary keys whose values are the user's own text (never parsed as numbers).
  character(len=*), parameter :: text_keys(2) = [character(len=5) :: 'case', 'title']

contains

  !> Set `error` if any number an output would hold is NaN or infinite.
  subroutine check_finite_outputs(deck, record, error)
    type(deck_t), intent(in) :: deck
    type(record_t), intent(in) :: record
    type(error_t), allocatable, intent(out) :: error
    call check_deck_numbers(deck, error)         ! first: a non-finite input explains a non-finite result
    if (allocated(error)) return
    call check_results(deck, record, error)
  end subroutine check_finite_outputs

  !> The run's results: summary, history, snapshots.
  subroutine check_results(deck, record, error)
    type(deck_t), intent(in) :: deck
    type(record_t), intent(in) :: record
    type(error_t), allocatable, intent(inout) :: error
    character(:), allocatable :: where, producer
    integer :: i, j
    where = ''
    producer = 'the '//analysis_name(deck%analysis)//' analysis'
    do i = 1, record%nsummary
      if (any(trim(record%summary(i)%key) == text_keys)) cycle
      if (.not. allocated(record%summary(i)%value)) cycle
      if (finite_text(record%summary(i)%value)) cycle
      where = 'summary key '//trim(record%summary(i)%key)//' = '//record%summary(i)%value
      if (index(record%summary(i)%key, 'hertz_') == 1) then
        producer = 'the Hertz reference of '//producer
      else if (index(record%summary(i)%key, 'expect_') == 1) then
        producer = 'an EXPECT check of '//producer
      end if
      exit
    end do
    if (len(where) == 0 .and. allocated(record%history) .and. allocated(record%columns)) then
      rows: do i = 1, record%nrow
        do j = 1, size(record%columns)
          if (ieee_is_finite(record%history(j, i))) cycle
          where = 'history column '//trim(record%columns(j))//' = '//non_finite_text(record%history(j, i))// &
                  ' in row '//integer_text(i)//' of '//integer_text(record%nrow)//row_place(record, i)
          exit rows
        end do
      end do rows
    end if
    if (len(where) == 0 .and. allocated(record%snapshots)) then
      do i = 1, size(record%snapshots)
        where = snapshot_problem(deck, record%snapshots(i))
        if (len(where) > 0) exit
      end do
    end if
    if (len(where) == 0 .and. allocated(record%pressure%values)) then
      if (.not. all(ieee_is_finite(record%pressure%values))) where = 'the contact pressure over radius '// &
        '(pressure.csv) holds '//integer_text(count(.not. ieee_is_finite(record%pressure%values)))//' non-finite value(s)'
    end if
    if (len(where) == 0) return
    call set_error(error, producer//' produced a non-finite result: '//where// &
                   '; no output is written (a NaN or an Infinity is never a result)', &
                   file=deck%cards%file, line=card_line(deck, 'ANALYSIS'), card=card_name(deck, 'ANALYSIS'))
  end subroutine check_results

  !> ' (step 12, t_s = 1.2E-004)': the row's step and time columns, where finite.
  function row_place(record, row) result(text)
    type(record_t), intent(in) :: record
    integer, intent(in) :: row
    character(:), allocatable :: text
    integer :: j
    text = ''
    do j = 1, min(2, size(record%columns))
      if (trim(record%columns(j)) /= 'step' .and. index(record%columns(j), 't_') /= 1) cycle
      if (.not. ieee_is_finite(record%history(j, row))) cycle
      if (len(text) > 0) text = text//', '
      if (trim(record%columns(j)) == 'step' .and. abs(record%history(j, row)) < 1.0e9_dp) then
        text = text//'step '//integer_text(nint(record%history(j, row)))
      else
        text = text//trim(record%columns(j))//' = '//table_real(record%history(j, row))
      end if
    end do
    if (len(text) > 0) text = ' ('//text//')'
  end function row_place

  !> '' or where a snapshot holds a non-finite number.
  function snapshot_problem(deck, snapshot) result(where)
    type(deck_t), intent(in) :: deck
    type(snapshot_t), intent(in) :: snapshot
    character(:), allocatable :: where, name
    name = 'snapshot'
    if (allocated(snapshot%name)) name = 'snapshot '//snapshot%name
    if (allocated(snapshot%label)) name = name//' ('//snapshot%label//')'
    where = ''
    if (.not. ieee_is_finite(snapshot%time)) then
      where = 'the time of '//name//' = '//non_finite_text(snapshot%time)
      return
    end if
    name = name//' at t = '//table_real(snapshot%time)//' s'
    if (allocated(snapshot%displacement)) where = nodal(snapshot%displacement, 'displacement')
    if (len(where) == 0 .and. allocated(snapshot%velocity)) where = nodal(snapshot%velocity, 'velocity')
    if (len(where) == 0 .and. allocated(snapshot%acceleration)) where = nodal(snapshot%acceleration, 'acceleration')
    if (len(where) == 0 .and. allocated(snapshot%stress)) where = nodal(snapshot%stress, 'stress')
    if (len(where) == 0 .and. allocated(snapshot%max_shear)) &
      where = nodal(reshape(snapshot%max_shear, [1, size(snapshot%max_shear)]), 'max_shear')
    if (len(where) == 0 .and. allocated(snapshot%von_mises)) &
      where = nodal(reshape(snapshot%von_mises, [1, size(snapshot%von_mises)]), 'von_mises')
    if (len(where) == 0 .and. allocated(snapshot%stress_gauss)) where = gauss(snapshot%stress_gauss)
  contains
    function nodal(values, field) result(text)
      real(dp), intent(in) :: values(:, :)
      character(*), intent(in) :: field
      character(:), allocatable :: text
      integer :: c, k
      text = ''
      do k = 1, size(values, 2)
        do c = 1, size(values, 1)
          if (ieee_is_finite(values(c, k))) cycle
          text = 'field '//field//' of '//name//' = '//non_finite_text(values(c, k))//' at '//node_name(k)// &
                 ', component '//integer_text(c)
          return
        end do
      end do
    end function nodal

    function gauss(values) result(text)
      real(dp), intent(in) :: values(:, :, :)
      character(:), allocatable :: text
      integer :: c, g, e
      text = ''
      do e = 1, size(values, 3)
        do g = 1, size(values, 2)
          do c = 1, size(values, 1)
            if (ieee_is_finite(values(c, g, e))) cycle
            text = 'field stress_gauss of '//name//' = '//non_finite_text(values(c, g, e))//' at '// &
                   element_name(e)//', Gauss point '//integer_text(g)//', component '//integer_text(c)
            return
          end do
        end do
      end do
    end function gauss

    function node_name(k) result(text)
      integer, intent(in) :: k
      character(:), allocatable :: text
      text = 'node index '//integer_text(k)
      if (allocated(deck%mesh%node_id)) then
        if (k <= size(deck%mesh%node_id)) text = 'node '//integer_text(deck%mesh%node_id(k))
      end if
    end function node_name

    function element_name(e) result(text)
      integer, intent(in) :: e
      character(:), allocatable :: text
      text = 'element index '//integer_text(e)
      if (allocated(deck%mesh%element_id)) then
        if (e <= size(deck%mesh%element_id)) text = 'element '//integer_text(deck%mesh%element_id(e))
      end if
    end function element_name
  end function snapshot_problem

  !> The deck's numbers that listing.txt and results.h5 echo, each located at its card.
  subroutine check_deck_numbers(deck, error)
    type(deck_t), intent(in) :: deck
    type(error_t), allocatable, intent(inout) :: error
    integer :: k, i
    if (allocated(deck%materials)) then
      do k = 1, size(deck%materials)
        associate (m => deck%materials(k))
        call check_values([m%young], 'Young modulus E(0) of material '//m%id, m%line, 'MATERIAL')
        call check_values([m%poisson], 'Poisson ratio nu(0) of material '//m%id, m%line, 'MATERIAL')
        call check_values([m%shear], 'shear modulus G(0) of material '//m%id, m%line, 'MATERIAL')
        call check_values([m%bulk], 'bulk modulus K of material '//m%id, m%line, 'MATERIAL')
        call check_values([m%density], 'density of material '//m%id, m%line, 'MATERIAL')
        call check_values([m%long_term_shear], 'long-term shear modulus G_inf of material '//m%id, m%line, 'MATERIAL')
        if (allocated(m%uniaxial_young)) call check_values([m%uniaxial_young, m%uniaxial_rate], &
                          'uniaxial terms (E_i, alpha_i) of material '//m%id, m%line, 'MATERIAL')
        if (allocated(m%prony_shear)) call check_values([m%prony_shear, m%prony_rate], &
                          'shear terms (G_m, beta_m) of material '//m%id, m%line, 'MATERIAL')
        end associate
        if (allocated(error)) return
      end do
    end if
    if (allocated(deck%stages)) then
      do k = 1, size(deck%stages)
        call check_values([deck%stages(k)%dt, deck%stages(k)%end_time], 'time stage (dt or end time)', &
                          deck%stages(k)%line, 'TIME')
        if (allocated(error)) return
      end do
    end if
    if (allocated(deck%loads%curves)) then
      do k = 1, size(deck%loads%curves)
        call check_values([deck%loads%curves(k)%time, deck%loads%curves(k)%value], &
                          'points of curve '//deck%loads%curves(k)%name, deck%loads%curves(k)%line, 'CURVE')
        if (allocated(error)) return
      end do
    end if
    if (allocated(deck%loads%fixes)) then
      do k = 1, size(deck%loads%fixes)
        call check_values(deck%loads%fixes(k)%value, 'prescribed displacement', deck%loads%fixes(k)%line, 'FIX')
        if (allocated(error)) return
      end do
    end if
    if (allocated(deck%loads%pressures)) then
      do k = 1, size(deck%loads%pressures)
        call check_values([deck%loads%pressures(k)%value], 'pressure', deck%loads%pressures(k)%line, 'PRESSURE')
        if (allocated(error)) return
      end do
    end if
    if (allocated(deck%loads%forces)) then
      do k = 1, size(deck%loads%forces)
        call check_values(deck%loads%forces(k)%value, 'force', deck%loads%forces(k)%line, 'FORCE')
        if (allocated(error)) return
      end do
    end if
    call check_values([deck%loads%gravity], 'gravity', deck%gravity_line, 'GRAVITY'); if (allocated(error)) return
    if (deck%plate%line > 0) call check_values([deck%plate%z], 'plate height', deck%plate%line, 'PLATE')
    if (allocated(error)) return
    if (deck%analysis == analysis_dynamic) then
      call check_values([deck%dynamics%theta], 'Wilson theta', deck%dynamics%wilson_line, 'WILSON')
      if (allocated(error)) return
      call check_values(deck%dynamics%acceleration, 'initial acceleration', deck%dynamics%initial_line, 'INITIAL')
      if (allocated(error)) return
      if (deck%dynamics%drop_line > 0) then
        call check_values(initial_velocity(deck), 'initial velocity of the drop', deck%dynamics%drop_line, 'DROP')
      else
        call check_values(initial_velocity(deck), 'initial velocity', deck%dynamics%initial_line, 'INITIAL')
      end if
      if (allocated(error)) return
    end if
    if (allocated(deck%mesh%xy)) then
      do i = 1, size(deck%mesh%xy, 2)
        if (all(ieee_is_finite(deck%mesh%xy(:, i)))) cycle
        call set_error(error, 'node '//integer_text(deck%mesh%node_id(i))//' has a non-finite coordinate (r, z) = ('// &
          table_real(deck%mesh%xy(1, i))//', '//table_real(deck%mesh%xy(2, i))//'); no output is written', &
          file=deck%cards%file, line=card_line(deck, mesh_card()), card=card_name(deck, mesh_card()))
        return
      end do
    end if
  contains
    !> The card that made the nodes: MESH for a generated mesh, else the first NODE card.
    function mesh_card() result(keyword)
      character(:), allocatable :: keyword
      keyword = 'NODE'
      if (allocated(deck%mesh%source)) then
        if (deck%mesh%source /= 'CARDS') keyword = 'MESH'
      end if
    end function mesh_card

    subroutine check_values(values, what, line, card)
      real(dp), intent(in) :: values(:)
      character(*), intent(in) :: what, card
      integer, intent(in) :: line
      integer :: j
      if (allocated(error)) return
      do j = 1, size(values)
        if (ieee_is_finite(values(j))) cycle
        if (line > 0) then
          call set_error(error, 'the '//what//' is '//non_finite_text(values(j))// &
            ' (beyond the range of double precision); no output is written', file=deck%cards%file, line=line, card=card)
        else
          call set_error(error, 'the '//what//' is '//non_finite_text(values(j))// &
            ' (beyond the range of double precision); no output is written', file=deck%cards%file)
        end if
        return
      end do
    end subroutine check_values
  end subroutine check_deck_numbers

  !> Line of the first card with this keyword (0 if none).
  integer function card_line(deck, keyword) result(line)
    type(deck_t), intent(in) :: deck
    character(*), intent(in) :: keyword
    integer :: i
    line = 0
    if (.not. allocated(deck%cards%cards)) return
    do i = 1, min(deck%cards%count, size(deck%cards%cards))
      if (.not. allocated(deck%cards%cards(i)%keyword)) cycle
      if (deck%cards%cards(i)%keyword == keyword) then
        line = deck%cards%cards(i)%line
        return
      end if
    end do
  end function card_line

  !> The keyword if the deck has such a card, else '' (an error then names no card).
  function card_name(deck, keyword) result(name)
    type(deck_t), intent(in) :: deck
    character(*), intent(in) :: keyword
    character(:), allocatable :: name
    name = ''
    if (card_line(deck, keyword) > 0) name = keyword
  end function card_name

  !> 'NaN', 'Infinity' or '-Infinity'.
  pure function non_finite_text(value) result(text)
    real(dp), intent(in) :: value
    character(:), allocatable :: text
    if (ieee_is_nan(value)) then
      text = 'NaN'
    else if (value > 0.0_dp) then
      text = 'Infinity'
    else if (value < 0.0_dp) then
      text = '-Infinity'
    else
      text = table_real(value)
    end if
  end function non_finite_text

  !> False if a summary value holds a non-finite number: a blank- or
  !> comma-separated word that reads as NaN or an infinity (NaN, Inf, +Infinity,
  !> ...) or as a number beyond double precision (1e999). Other words are text.
  function finite_text(value) result(finite)
    character(*), intent(in) :: value
    logical :: finite
    integer :: first, last, n
    finite = .true.
    n = len(value)
    first = 1
    do while (first <= n)
      if (index(' ,;()', value(first:first)) > 0) then
        first = first + 1
        cycle
      end if
      last = first
      do while (last < n)
        if (index(' ,;()', value(last + 1:last + 1)) > 0) exit
        last = last + 1
      end do
      if (.not. finite_word(value(first:last))) then
        finite = .false.
        return
      end if
      first = last + 1
    end do
  end function finite_text

  !> False for a word that is a non-finite number.
  logical function finite_word(word) result(finite)
    character(*), intent(in) :: word
    character(len=len(word)) :: upper
    integer :: i, code, start
    real(dp) :: number
    integer :: status
    finite = .true.
    upper = word
    do i = 1, len(word)
      code = iachar(word(i:i))
      if (code >= iachar('a') .and. code <= iachar('z')) upper(i:i) = achar(code - 32)
    end do
    start = 1
    if (upper(1:1) == '+' .or. upper(1:1) == '-') start = 2
    if (start > len(upper)) return
    select case (upper(start:))
    case ('NAN', 'INF', 'INFINITY')
      finite = .false.
      return
    end select
    if (index('0123456789.', upper(start:start)) == 0) return     ! a word, not a number
    if (verify(upper(start:), '0123456789.E+-D') /= 0) return       ! '1.5e3mm' and the like: text
    read(word, *, iostat=status) number
    if (status == 0) finite = ieee_is_finite(number)                 ! '0.1.0' does not read: text
  end function finite_word
end module visco2d_output_check
