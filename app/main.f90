!> visco2d command line:
!>   visco2d [options] DECK...     run decks into OUT/<deck stem>/
!>   visco2d check DECK...         parse and check, print mesh statistics and effects
!>   visco2d --decks-from LIST     the deck paths one per line in the file LIST; with LIST -,
!>                                 read from standard input and each run as its line arrives
!>   visco2d relax --nu NU E1 ALPHA1 [E2 ALPHA2 ...]
!>                                 exact shear relaxation series of a uniaxial one (eq. [48])
program visco2d
  use visco2d_kinds, only: dp
  use visco2d_error, only: error_t, error_text
  use visco2d_record, only: record_t
  use visco2d_driver, only: run_deck, check_deck
  use visco2d_expect, only: run_line, expect_tally_t, missed_expect, miss_report, expect_missed_status
  use visco2d_batch, only: duplicate_case_message
  use visco2d_case_folder, only: prepare_output_root
  use visco2d_system, only: ignore_file_size_signal, install_interrupt_cleanup, get_argument
  use visco2d_cards, only: parse_real
  use visco2d_card_reader, only: read_line
  use visco2d_driver, only: case_name_of
  use visco2d_relaxation, only: uniaxial_to_shear
  use visco2d_strings, only: integer_text
  use visco2d_timers, only: timers_enable
  use visco2d_progress, only: progress_configure, progress_auto, progress_on, progress_off
  use visco2d_budget, only: set_memory_limit, set_time_limit, read_limit_environment
  use, intrinsic :: iso_c_binding, only: c_int
  use, intrinsic :: iso_fortran_env, only: iostat_end
  implicit none
  interface
    subroutine c_exit(status) bind(c, name='exit')
      import :: c_int
      integer(c_int), value :: status
    end subroutine c_exit
  end interface
  character(:), allocatable :: out_root, argument, message, list
  character(len=:), allocatable :: decks(:)
  integer :: i, count, failed, missed, length, streamed
  logical :: quiet, checking, progress
  type(error_t), allocatable :: error

  call ignore_file_size_signal()        ! past a file size limit a write fails and is reported (exit 1)
  call install_interrupt_cleanup()      ! an interrupt while a case folder is written leaves no partial folder
  out_root = 'out'
  quiet = .false.
  progress = .false.
  checking = .false.
  list = ''
  if (command_argument_count() >= 1) then
    call get_argument(1, argument)
    if (argument == 'relax') call run_relax()
  end if
  allocate(character(len=4096) :: decks(command_argument_count()))
  count = 0
  i = 1
  do while (i <= command_argument_count())
    call get_argument(i, argument)
    select case (argument)
    case ('-h', '--help')
      call print_help()
      stop
    case ('--version')
      print '(a)', 'visco2d 0.1.0'
      stop
    case ('-o', '--out')
      if (i == command_argument_count()) call usage_error('option '//argument//' needs a folder')
      i = i + 1
      call get_argument(i, out_root)
    case ('-q', '--quiet')
      quiet = .true.
    case ('--progress')
      progress = .true.
    case ('--timing')
      call timers_enable(.true.)
    case ('--decks-from')
      if (i == command_argument_count()) call usage_error('option '//argument//' needs a file of deck paths, or - for stdin')
      if (len(list) > 0) call usage_error('option --decks-from is given twice')
      i = i + 1
      call get_argument(i, list)
      if (len(list) == 0) call usage_error('the file given with --decks-from is empty: give a file of deck paths, or -')
    case ('--max-memory')
      if (i == command_argument_count()) call usage_error('option '//argument//' needs a size (e.g. 8G)')
      i = i + 1
      call get_argument(i, argument)
      call set_memory_limit(argument, '--max-memory', message)
      if (len(message) > 0) call usage_error(message)
    case ('--max-time')
      if (i == command_argument_count()) call usage_error('option '//argument//' needs a number of seconds')
      i = i + 1
      call get_argument(i, argument)
      call set_time_limit(argument, '--max-time', message)
      if (len(message) > 0) call usage_error(message)
    case ('check')
      if (count == 0 .and. .not. checking) then
        checking = .true.
      else
        count = count + 1
        decks(count) = argument
      end if
    case default
      if (argument(1:1) == '-') call usage_error('unknown option '//argument)
      count = count + 1
      decks(count) = argument
    end select
    i = i + 1
  end do
  call read_limit_environment(message)      ! a bad VISCO2D_MAX_MEMORY / VISCO2D_MAX_TIME: as a bad option
  if (len(message) > 0) call usage_error(message)
  if (list == '-') then
    if (count > 0) call usage_error('with --decks-from - the decks come from standard input only: '// &
      'give no deck on the command line')
  else if (len(list) > 0) then
    call read_deck_list(list)
  end if
  if (count == 0 .and. list /= '-') call usage_error('no deck given')
  if (.not. checking) then
    message = duplicate_case_message(decks(1:count), out_root)    ! no silent overwrite of a case folder
    if (len(message) > 0) call usage_error(message)
    call prepare_output(out_root)
  end if
  call configure_progress()

  failed = 0
  missed = 0
  if (list == '-') then
    call run_streamed()
    count = streamed
  else
    do i = 1, count
      length = len_trim(decks(i))
      call run_or_check(decks(i)(1:length))
    end do
  end if
  if (count > 1 .and. failed > 0) write(0, '(a, i0, a, i0, a)') 'visco2d: ', failed, ' of ', count, ' decks failed'
  if (count > 1 .and. missed > 0) write(0, '(a, i0, a, i0, a)') 'visco2d: ', missed, ' of ', count, &
    ' decks missed their own EXPECT cards (their results are written)'
  flush(6)
  flush(0)
  deallocate(decks, out_root)                 ! everything freed before exit (valgrind: nothing lost)
  if (allocated(argument)) deallocate(argument)
  if (allocated(message)) deallocate(message)
  if (allocated(list)) deallocate(list)
  if (failed > 0) call c_exit(1_c_int)
  if (missed > 0) call c_exit(int(expect_missed_status, c_int))     ! every deck ran; an EXPECT card missed

contains

  !> One deck, checked or run; a failure is counted and printed as "visco2d: error: ..." on stderr.
  subroutine run_or_check(path)
    character(*), intent(in) :: path
    if (checking) then
      call check_deck(path, error)
    else
      call run_one(path, error)
    end if
    if (allocated(error)) then
      failed = failed + 1
      write(0, '(a)') 'visco2d: error: '//error_text(error)
      deallocate(error)
    end if
    flush(6)
    flush(0)
  end subroutine run_or_check

  !> --decks-from FILE: its deck paths, one per line (blank lines and lines
  !> starting with # skipped), after those of the command line. A file that
  !> cannot be read is a usage error (exit status 2), before any deck runs.
  subroutine read_deck_list(path)
    character(*), intent(in) :: path
    character(:), allocatable :: line
    character(len=512) :: reason
    character(len=:), allocatable :: bigger(:)
    integer :: unit, ios, number
    open(newunit=unit, file=path, status='old', action='read', iostat=ios, iomsg=reason)
    if (ios /= 0) call usage_error('--decks-from '//path//': cannot open it: '//trim(reason))
    number = 0
    do
      call read_line(unit, line, ios, reason)
      if (ios /= 0) exit
      number = number + 1
      line = deck_path_of(line)
      if (len(line) == 0) cycle
      if (len(line) > len(decks)) call usage_error(path//':'//integer_text(number)// &
        ': a deck path longer than '//integer_text(len(decks))//' characters')
      if (count == size(decks)) then
        allocate(character(len=len(decks)) :: bigger(max(16, 2*size(decks))))
        bigger(1:count) = decks(1:count)
        call move_alloc(bigger, decks)
      end if
      count = count + 1
      decks(count) = line
    end do
    if (ios /= iostat_end) call usage_error(path//':'//integer_text(number + 1)//': cannot read it: '//trim(reason))
    close(unit)
  end subroutine read_deck_list

  !> --decks-from -: each line of standard input a deck, run (or checked) as
  !> soon as its line is read, so a program can keep one visco2d process busy
  !> with the decks of a sweep (visco2d-batch does: doc/batch.md). Two decks
  !> with one case name: the second is refused (an error of that deck) rather
  !> than replacing the first one's folder.
  subroutine run_streamed()
    character(:), allocatable :: line, name
    character(len=512) :: reason
    character(len=:), allocatable :: names(:), bigger(:)
    integer, allocatable :: lengths(:)
    integer :: ios, k, remembered
    logical :: seen
    streamed = 0
    remembered = 0                                  ! the case names run so far: names(1:remembered)
    allocate(character(len=256) :: names(64))
    allocate(lengths(64))
    do
      call read_line(5, line, ios, reason)
      if (ios /= 0) exit
      line = deck_path_of(line)
      if (len(line) == 0) cycle
      streamed = streamed + 1
      name = case_name_of(line)
      seen = .false.
      do k = 1, remembered                          ! the lengths first: most names differ there
        if (lengths(k) /= len(name)) cycle
        if (names(k)(1:lengths(k)) == name) then
          seen = .true.
          exit
        end if
      end do
      if (seen) then
        failed = failed + 1
        write(0, '(a)') 'visco2d: error: '//line//': the case name "'//name//'" was run earlier in this batch: '// &
          'its folder '//out_root//'/'//name//'/ would be replaced; give each deck once, with its own name'
        flush(0)
        cycle
      end if
      if (remembered == size(names) .or. len(name) > len(names)) then
        allocate(character(len=max(len(names), len(name))) :: bigger(max(size(names), 2*remembered)))
        bigger(1:remembered) = names(1:remembered)
        call move_alloc(bigger, names)
        lengths = [lengths(1:remembered), (0, k = remembered + 1, size(names))]
      end if
      remembered = remembered + 1
      names(remembered) = name
      lengths(remembered) = len(name)
      call run_or_check(line)
    end do
    if (ios /= iostat_end) then
      write(0, '(a)') 'visco2d: error: standard input (--decks-from -): cannot read it: '//trim(reason)
      failed = failed + 1
    end if
  end subroutine run_streamed

  !> A line of a deck list as a path: without a trailing carriage return and
  !> blanks; '' for a blank line or a # comment.
  function deck_path_of(line) result(path)
    character(*), intent(in) :: line
    character(:), allocatable :: path
    path = line
    if (len(path) > 0) then
      if (path(len(path):len(path)) == achar(13)) path = path(1:len(path) - 1)
    end if
    path = trim(path)
    if (len(adjustl(path)) == 0) then
      path = ''
    else if (path(1:1) == '#') then
      path = ''
    end if
  end function deck_path_of

  !> Run a deck; print its one-line result unless quiet (the record is freed on return).
  subroutine run_one(path, error)
    character(*), intent(in) :: path
    type(error_t), allocatable, intent(out) :: error
    type(record_t) :: record
    type(expect_tally_t) :: tally
    call run_deck(path, out_root, record, error, tally)
    if (allocated(error)) return
    if (.not. quiet) print '(a)', run_line(record, tally)
    if (missed_expect(tally)) then
      missed = missed + 1
      flush(6)
      write(0, '(a)') miss_report(tally)
    end if
  end subroutine run_one

  !> Before any deck runs: the output root must be named and writable (exit
  !> status 2, as for usage errors); folders that dead runs left in it are removed.
  subroutine prepare_output(root)
    character(*), intent(in) :: root
    type(error_t), allocatable :: problem
    if (len_trim(root) == 0) call usage_error('the output folder given with -o is empty: give a folder, e.g. -o out')
    call prepare_output_root(root, problem)
    if (allocated(problem)) then
      write(0, '(a)') 'visco2d: error: '//error_text(problem)
      flush(0)
      call c_exit(2_c_int)
    end if
  end subroutine prepare_output

  !> Progress on stderr: --progress forces it on; otherwise -q turns it off;
  !> otherwise it shows when stderr is a terminal. VISCO2D_PROGRESS_DELAY
  !> (seconds, default 2) is the wall time before the first line.
  subroutine configure_progress()
    character(:), allocatable :: text
    real(dp) :: delay
    integer :: n, status
    logical :: ok
    delay = 2.0_dp
    call get_environment_variable('VISCO2D_PROGRESS_DELAY', length=n, status=status)
    if (status == 0 .and. n > 0) then
      allocate(character(len=n) :: text)
      call get_environment_variable('VISCO2D_PROGRESS_DELAY', text)
      call parse_real(text, delay, ok)
      if (.not. ok .or. delay < 0.0_dp) then
        write(0, '(a)') 'visco2d: warning: VISCO2D_PROGRESS_DELAY="'//text// &
          '" is not a number of seconds >= 0; using 2'
        delay = 2.0_dp
      end if
    end if
    if (progress) then
      call progress_configure(progress_on, delay)
    else if (quiet) then
      call progress_configure(progress_off, delay)
    else
      call progress_configure(progress_auto, delay)
    end if
  end subroutine configure_progress

  !> A usage error (of the relax subcommand if `relax`): message and usage on stderr, exit status 2.
  subroutine usage_error(message, relax)
    character(*), intent(in) :: message
    logical, intent(in), optional :: relax
    logical :: for_relax
    for_relax = .false.
    if (present(relax)) for_relax = relax
    if (for_relax) then
      write(0, '(a)') 'visco2d relax: '//message
      write(0, '(a)') 'usage: visco2d relax --nu NU E1 ALPHA1 [E2 ALPHA2 ...]   (Pa, 1/s; see visco2d --help)'
    else
      write(0, '(a)') 'visco2d: '//message
      write(0, '(a)') 'usage: visco2d [-o DIR] [-q] [--progress] DECK...   |   visco2d check DECK...   |   visco2d --help'
    end if
    flush(0)
    call c_exit(2_c_int)
  end subroutine usage_error

  !> visco2d relax --nu NU E1 ALPHA1 [E2 ALPHA2 ...]: the uniaxial Prony series
  !> (eq. [47]) to the exact shear series (eqs. [48]-[49]). stdout holds only
  !> "K = <Pa>" and one "G_m beta_m" line per term, so scripts can read it.
  subroutine run_relax()
    real(dp), allocatable :: values(:), shear(:), beta(:)
    real(dp) :: poisson, bulk
    character(:), allocatable :: option, text
    type(error_t), allocatable :: conversion
    logical :: have_poisson, ok
    integer :: position, count, m

    allocate(values(command_argument_count()))
    count = 0
    poisson = 0.0_dp
    have_poisson = .false.
    position = 2
    do while (position <= command_argument_count())
      call get_argument(position, option)
      if (option == '--nu' .or. index(option, '--nu=') == 1) then
        if (have_poisson) call usage_error('--nu is given twice', relax=.true.)
        if (option == '--nu') then
          if (position == command_argument_count()) call usage_error('option --nu needs a value', relax=.true.)
          position = position + 1
          call get_argument(position, text)
        else
          text = option(6:)
        end if
        call parse_real(text, poisson, ok)
        if (.not. ok) call usage_error('--nu: "'//text//'" is not a finite number', relax=.true.)
        have_poisson = .true.
      else if (option == '-h' .or. option == '--help') then
        call print_help()
        stop
      else
        count = count + 1
        call parse_real(option, values(count), ok)
        if (.not. ok) then
          if (index(option, '-') == 1) call usage_error('unknown option '//option, relax=.true.)
          call usage_error('value '//integer_text(count)//' ("'//option//'") is not a finite number', relax=.true.)
        end if
      end if
      position = position + 1
    end do
    if (.not. have_poisson) call usage_error("missing --nu NU (Poisson's ratio at t = 0)", relax=.true.)
    if (count == 0) call usage_error('no terms: give pairs E ALPHA (Pa, 1/s)', relax=.true.)
    if (mod(count, 2) /= 0) &
      call usage_error('an odd number of values ('//integer_text(count)//'): expected pairs E ALPHA', relax=.true.)

    call uniaxial_to_shear(values(1:count:2), values(2:count:2), poisson, bulk, shear, beta, conversion)
    if (allocated(conversion)) then
      write(0, '(a)') 'visco2d relax: '//error_text(conversion)
      flush(0)
      call c_exit(1_c_int)
    end if
    print '(a)', 'K = '//scientific(bulk)
    do m = 1, size(shear)
      print '(a)', scientific(shear(m))//'  '//scientific(beta(m))
    end do
    flush(6)
    stop
  end subroutine run_relax

  !> A real with 12 significant digits, no blanks (es format, 3-digit exponent).
  function scientific(value) result(text)
    real(dp), intent(in) :: value
    character(:), allocatable :: text
    character(len=32) :: buffer
    write(buffer, '(es19.11e3)') value
    text = trim(adjustl(buffer))
  end function scientific

  subroutine print_help()
    print '(a)', 'visco2d - axisymmetric / plane-strain viscoelastic finite elements (fruit impact)'
    print '(a)', ''
    print '(a)', 'usage:'
    print '(a)', '  visco2d [options] DECK...   run each card deck; results go to OUT/<deck name>/'
    print '(a)', '  visco2d check DECK...       read and check decks without solving; print the mesh'
    print '(a)', '                              statistics (nodes, elements, half-bandwidth) and the'
    print '(a)', '                              active effects'
    print '(a)', '  visco2d relax --nu NU E1 ALPHA1 [E2 ALPHA2 ...]'
    print '(a)', '                              exact shear relaxation G(t) = sum G_m exp(-beta_m t)'
    print '(a)', '                              of E(t) = sum E_i exp(-alpha_i t), eq. [48], with'
    print '(a)', '                              K = sum E_i/(3(1 - 2 NU)); SI units (Pa, 1/s).'
    print '(a)', '                              Prints "K = <Pa>", then "G_m beta_m" per term by'
    print '(a)', '                              increasing beta (--nu=NU works too). Exit status 2:'
    print '(a)', '                              usage (no --nu, odd count, not a finite number); 1: invalid'
    print '(a)', '                              values (E <= 0, ALPHA < 0, NU outside (-1, 0.5))'
    print '(a)', ''
    print '(a)', 'options:'
    print '(a)', '  -o, --out DIR   output root folder (default: out)'
    print '(a)', '  -q, --quiet     do not print the one-line result of each deck (and no progress)'
    print '(a)', '  --progress      show the progress of runs longer than 2 s on stderr (step,'
    print '(a)', '                  t, alpha, ~time left) even with -q or when stderr is not a'
    print '(a)', '                  terminal (whole lines, one a second, for logs); by default'
    print '(a)', '                  it shows only when stderr is a terminal. The delay before'
    print '(a)', '                  the first line: VISCO2D_PROGRESS_DELAY=<seconds> (default 2)'
    print '(a)', '  --timing        print the time of each phase of each run (make bench)'
    print '(a)', '  --decks-from LIST'
    print '(a)', '                  the deck paths one per line in the file LIST (blank lines and'
    print '(a)', '                  # comments skipped), after those of the command line; with'
    print '(a)', '                  LIST = -, read from standard input, each deck run as soon as'
    print '(a)', '                  its line arrives (one process kept busy by a program feeding it)'
    print '(a)', '  --max-memory SIZE'
    print '(a)', '                  refuse a deck whose run is estimated to need more memory than'
    print '(a)', '                  SIZE (e.g. 8G, 512M; K, M, G, T are powers of 1024). Also'
    print '(a)', '                  VISCO2D_MAX_MEMORY=SIZE; the default is half of the machine''s'
    print '(a)', '                  memory, and no run may need more than all of it (or than'
    print '(a)', '                  ulimit -v allows). `check` prints the estimate (memory,'
    print '(a)', '                  output size, a rough run time); a run estimated past 20 s'
    print '(a)', '                  is announced by a note on stderr'
    print '(a)', '  --max-time SECONDS'
    print '(a)', '                  refuse a deck whose run is estimated (roughly, within a factor'
    print '(a)', '                  of 2) to take longer than SECONDS on one core. Also'
    print '(a)', '                  VISCO2D_MAX_TIME=SECONDS; no limit by default'
    print '(a)', '  -h, --help      this text'
    print '(a)', '      --version   program version'
    print '(a)', ''
    print '(a)', 'Each case folder holds listing.txt, summary.txt (key = value), history.csv and'
    print '(a)', 'results.h5, written under OUT/.<case>.partial.<pid>/ and moved into place only when'
    print '(a)', 'all four are complete: a deck that fails (an error, a non-finite result, a full'
    print '(a)', 'disk, an interrupt) leaves no case folder behind and an older one as it was. The'
    print '(a)', 'run goes on with the next deck; the exit status is 1 if any deck failed, 2 for'
    print '(a)', 'usage errors and an output folder that is empty or cannot be written (checked'
    print '(a)', 'before any deck runs), 3 if every deck ran but one missed its own EXPECT cards'
    print '(a)', '(its results are written; the misses are on stderr, as errors). Folders left'
    print '(a)', 'by runs that no longer exist are removed.'
    print '(a)', 'Two decks of a batch with the same case name (the file name without its'
    print '(a)', 'extension) would write one folder: the batch is refused (exit status 2).'
    print '(a)', 'Errors read  file:line:column: CARD: message.  The cards: doc/cards.md.'
  end subroutine print_help
end program visco2d
