!> The EXPECT cards of a deck checked against the run's summary (their
!> expect_<key>_value, _rel_error and _within_rtol keys and the tally of a
!> run), the one-line report of a run, and the summary value of a key.
module visco2d_expect
  use visco2d_kinds, only: dp
  use visco2d_error, only: error_t, set_error, error_text
  use visco2d_strings, only: integer_text, message_real, to_upper, to_lower, short_real
  use visco2d_deck, only: deck_t, expect_t
  use visco2d_record, only: record_t, record_put, record_put_real
  use visco2d_output_check, only: finite_text
  implicit none
  private

  public :: expect_tally_t, check_expect_cards, check_expectations, relative_error, run_line, summary_value
  public :: missed_expect, miss_report

  !> The EXPECT checks of a run: one per EXPECT card (the summary holds their
  !> expect_<key>_value, _rel_error and _within_rtol keys). A deck that
  !> misses one (within < count) still writes its case folder; the programs
  !> print `misses` on stderr and exit with status 3 (expect_missed_status).
  type :: expect_tally_t
    integer :: count = 0          !< EXPECT cards checked
    integer :: within = 0         !< of them within their RTOL
    real(dp) :: worst = 0.0_dp    !< the largest relative error
    character(:), allocatable :: misses   !< `visco2d: error: ` lines, one per card outside its RTOL
  end type expect_tally_t

  !> The exit status of a run whose decks all ran, one or more of them
  !> outside the RTOL of its own EXPECT cards (1, a deck that failed, wins).
  integer, parameter, public :: expect_missed_status = 3

contains

  !> A second EXPECT card for the same key would overwrite the first's summary
  !> keys: refused before solving (an expected value of 0 or not finite is
  !> refused by the card reader).
  subroutine check_expect_cards(deck, error)
    type(deck_t), intent(in) :: deck
    type(error_t), allocatable, intent(inout) :: error
    integer :: k, j
    if (.not. allocated(deck%expects)) return
    do k = 1, size(deck%expects)
      associate (expect => deck%expects(k))
      do j = 1, k - 1
        if (deck%expects(j)%key /= expect%key) cycle
        call set_error(error, 'key '//to_lower(expect%key)//' is already expected on line '// &
          integer_text(deck%expects(j)%line)//' (one EXPECT card per key)', file=deck%cards%file, line=expect%line, &
          column=positional_column(deck, expect%line, 1), card='EXPECT')
        return
      end do
      end associate
    end do
  end subroutine check_expect_cards

  !> Column of the n-th positional field of the card on a line (0 if unknown):
  !> on an EXPECT card, 1 is the key and 2 the value.
  integer function positional_column(deck, line, n) result(column)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: line, n
    integer :: i, t, positional
    column = 0
    if (.not. allocated(deck%cards%cards)) return
    do i = 1, min(deck%cards%count, size(deck%cards%cards))
      if (deck%cards%cards(i)%line /= line .or. .not. allocated(deck%cards%cards(i)%tokens)) cycle
      positional = 0
      do t = 1, size(deck%cards%cards(i)%tokens)
        if (.not. allocated(deck%cards%cards(i)%tokens(t)%name)) cycle
        if (len(deck%cards%cards(i)%tokens(t)%name) > 0) cycle
        positional = positional + 1
        if (positional == n) then
          column = deck%cards%cards(i)%tokens(t)%column
          return
        end if
      end do
    end do
  end function positional_column

  !> Compare the EXPECT cards with the summary; record per key the expected
  !> value, the relative error and whether it is within RTOL; count the checks in `tally`.
  subroutine check_expectations(deck, record, tally, error)
    type(deck_t), intent(in) :: deck
    type(record_t), intent(inout) :: record
    type(expect_tally_t), intent(out) :: tally
    type(error_t), allocatable, intent(inout) :: error
    integer :: k, i, ios
    real(dp) :: computed, relative
    logical :: found
    do k = 1, size(deck%expects)
      found = .false.
      do i = 1, record%nsummary
        if (to_upper(trim(record%summary(i)%key)) /= deck%expects(k)%key) cycle
        if (.not. finite_text(record%summary(i)%value)) then
          call set_error(error, 'key "'//to_lower(deck%expects(k)%key)//'" is '//record%summary(i)%value// &
            ' in this run: it cannot be compared', file=deck%cards%file, line=deck%expects(k)%line, &
            column=positional_column(deck, deck%expects(k)%line, 1), card='EXPECT')
          return
        end if
        read(record%summary(i)%value, *, iostat=ios) computed
        if (ios /= 0) exit
        found = .true.
        relative = relative_error(computed, deck%expects(k)%value)
        tally%count = tally%count + 1
        tally%worst = max(tally%worst, relative)
        if (relative <= deck%expects(k)%tolerance) then
          tally%within = tally%within + 1
        else
          call add_miss(tally, deck, deck%expects(k), trim(record%summary(i)%key), record%summary(i)%value, relative)
        end if
        call record_put_real(record, 'expect_'//trim(record%summary(i)%key)//'_value', deck%expects(k)%value)
        call record_put_real(record, 'expect_'//trim(record%summary(i)%key)//'_rel_error', relative)
        call record_put(record, 'expect_'//trim(record%summary(i)%key)//'_within_rtol', &
                        trim(merge('yes', 'no ', relative <= deck%expects(k)%tolerance)))
        exit
      end do
      if (.not. found) then
        call set_error(error, 'key "'//to_lower(deck%expects(k)%key)//'" is not a numeric summary key '// &
          'of this run (see summary.txt for the keys)', file=deck%cards%file, line=deck%expects(k)%line, &
          column=deck%expects(k)%column, card='EXPECT')
        return
      end if
    end do
  end subroutine check_expectations

  !> One line of tally%misses: the card, the computed and expected values,
  !> the relative error and the RTOL it missed.
  subroutine add_miss(tally, deck, expect, key, computed, relative)
    type(expect_tally_t), intent(inout) :: tally
    type(deck_t), intent(in) :: deck
    type(expect_t), intent(in) :: expect
    character(*), intent(in) :: key, computed       !< the summary key as spelt there, its value
    real(dp), intent(in) :: relative
    type(error_t), allocatable :: miss
    call set_error(miss, key//' = '//trim(adjustl(computed))//' is not within RTOL = '// &
      short_real(expect%tolerance)//' of the expected '//short_real(expect%value)//' (relative error '// &
      message_real(relative)//'): the deck misses its own EXPECT card (its results are written)', &
      file=deck%cards%file, line=expect%line, column=positional_column(deck, expect%line, 2), card='EXPECT')
    if (.not. allocated(tally%misses)) tally%misses = ''
    if (len(tally%misses) > 0) tally%misses = tally%misses//new_line('a')
    tally%misses = tally%misses//'visco2d: error: '//error_text(miss)
  end subroutine add_miss

  !> The run missed one of its EXPECT cards (outside its RTOL).
  pure logical function missed_expect(tally)
    type(expect_tally_t), intent(in) :: tally
    missed_expect = tally%within < tally%count
  end function missed_expect

  !> The misses as the programs print them on stderr, one line per card:
  !> `visco2d: error: file:line:column: EXPECT: ...` ('' if none).
  function miss_report(tally) result(text)
    type(expect_tally_t), intent(in) :: tally
    character(:), allocatable :: text
    text = ''
    if (allocated(tally%misses)) text = tally%misses
  end function miss_report

  !> |computed - expected| / |expected| for finite values and expected /= 0,
  !> without overflow: values beyond huge/4 are halved first (exact, so the
  !> result is that of the formula); a ratio above relative_error_ceiling
  !> (1e300: an expected value near the underflow limit) is reported as the
  !> ceiling, which no RTOL accepts.
  pure real(dp) function relative_error(computed, expected) result(relative)
    real(dp), intent(in) :: computed, expected
    real(dp), parameter :: relative_error_ceiling = 1.0e300_dp
    real(dp) :: scale, difference, reference
    relative = 0.0_dp
    if (computed == expected) return
    scale = 1.0_dp
    if (max(abs(computed), abs(expected)) > 0.25_dp*huge(1.0_dp)) scale = 0.5_dp
    difference = abs(scale*computed - scale*expected)
    reference = scale*abs(expected)
    if (difference >= reference*relative_error_ceiling) then
      relative = relative_error_ceiling
    else
      relative = difference/reference
    end if
  end function relative_error

  !> The one-line report printed for a deck by the command line program:
  !> case, mesh size, the main result, the EXPECT checks (one per EXPECT card,
  !> from run_deck's tally) and the CPU time.
  function run_line(record, tally) result(line)
    type(record_t), intent(in) :: record
    type(expect_tally_t), intent(in) :: tally
    character(:), allocatable :: line
    character(len=16) :: buffer
    line = summary_value(record, 'case')//': '//summary_value(record, 'nodes')//' nodes, '// &
      summary_value(record, 'elements')//' elements, half-bandwidth '//summary_value(record, 'half_bandwidth')
    if (len(summary_value(record, 'alpha_max_mm')) > 0) then          ! an impact: what a batch user looks for
      line = line//'; alpha_m = '//four_digits(summary_value(record, 'alpha_max_mm'))//' mm at '// &
        four_digits(summary_value(record, 't_alpha_max_ms'))//' ms, q_m = '// &
        four_digits(summary_value(record, 'q_max_MPa'))//' MPa'
      if (len(summary_value(record, 'bruise_volume_cm3')) > 0) &
        line = line//', bruise '//four_digits(summary_value(record, 'bruise_volume_cm3'))//' cm3'
    else if (len(summary_value(record, 'max_displacement_m')) > 0) then
      line = line//'; max |u| = '//summary_value(record, 'max_displacement_m')//' m'
    end if
    if (summary_value(record, 'warnings') /= '0' .and. len(summary_value(record, 'warnings')) > 0) &
      line = line//'; '//summary_value(record, 'warnings')//' warning(s)'
    if (tally%count > 0) then
      write(buffer, '(es10.2e3)') tally%worst
      line = line//'; EXPECT '//integer_text(tally%within)//'/'//integer_text(tally%count)//' within RTOL (worst rel. error '// &
             trim(adjustl(buffer))//')'
    end if
    line = line//'; cpu '//summary_value(record, 'cpu_s')//' s'
  end function run_line

  !> A summary number with four significant digits (the text as it is if it is not a number).
  function four_digits(text) result(short)
    character(*), intent(in) :: text
    character(:), allocatable :: short
    real(dp) :: value
    integer :: ios
    character(len=32) :: buffer
    short = text
    read(text, *, iostat=ios) value
    if (ios /= 0) return
    if (abs(value) >= 1.0e-3_dp .and. abs(value) < 1.0e5_dp .or. value == 0.0_dp) then
      write(buffer, '(g0.4)') value
    else
      write(buffer, '(es10.3e3)') value
    end if
    short = trim(adjustl(buffer))
  end function four_digits

  !> The text of a summary key ('' if absent).
  function summary_value(record, key) result(value)
    type(record_t), intent(in) :: record
    character(*), intent(in) :: key
    character(:), allocatable :: value
    integer :: i
    value = ''
    do i = 1, record%nsummary
      if (trim(record%summary(i)%key) == key) value = record%summary(i)%value
    end do
  end function summary_value

end module visco2d_expect
