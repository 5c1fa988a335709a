!> visco2d-farm: the decks of a batch run over MPI ranks (a task farm).
!>   mpirun -np N visco2d-farm [-q] [-o OUT] DECK...
!> runs the decks as `visco2d [-q] [-o OUT] DECK...` runs them serially: the
!> same OUT/<case>/ folders, the same one-line result per deck on stdout in
!> deck order (rank 0 prints them), the same errors on stderr, exit status 1
!> if any deck failed, 2 on usage errors, 3 if every deck ran but one missed
!> its own EXPECT cards. Rank 0 checks the command line and
!> prepares the output root before any work; with more than one rank it is a
!> dispatcher that hands out deck indices one at a time to the ranks that ask
!> (dynamic scheduling: a long deck holds up no other) and prints the results
!> in deck order as they come; every other rank runs the decks it is given
!> in-process (run_batch_deck). With one rank, rank 0 runs every deck itself.
!> Built with MPI only by `make mpi` (mpif90 and -DVISCO2D_MPI); the default
!> build makes a program that says so and exits with status 2.
program visco2d_farm
#ifdef VISCO2D_MPI
  use mpi_f08, only: MPI_Init, MPI_Finalize, MPI_Comm_rank, MPI_Comm_size, MPI_Bcast, MPI_Send, MPI_Recv, &
                     MPI_Irecv, MPI_Test, MPI_Request, MPI_Status, MPI_COMM_WORLD, MPI_INTEGER, MPI_CHARACTER, &
                     MPI_ANY_SOURCE, MPI_STATUS_IGNORE
  use visco2d_kinds, only: dp
  use visco2d_error, only: error_t, error_text
  use visco2d_batch, only: duplicate_case_message, run_batch_deck
  use visco2d_expect, only: expect_missed_status
  use visco2d_case_folder, only: prepare_output_root
  use visco2d_system, only: ignore_file_size_signal, install_interrupt_cleanup, get_argument
  use visco2d_progress, only: progress_configure, progress_off
#endif
  use, intrinsic :: iso_c_binding, only: c_int
  implicit none
  interface
    subroutine c_exit(status) bind(c, name='exit')
      import :: c_int
      integer(c_int), value :: status
    end subroutine c_exit
  end interface
#ifdef VISCO2D_MPI
  interface
    function c_usleep(microseconds) bind(c, name='usleep') result(status)
      import :: c_int
      integer(c_int), value :: microseconds
      integer(c_int) :: status
    end function c_usleep
  end interface
  integer, parameter :: tag_report = 1, tag_text = 2, tag_work = 3   !< message tags
  integer, parameter :: go = 0, stop_ok = 1, stop_usage = 2           !< rank 0's verdict on the command line
  !> A deck's result as rank 0 keeps it until its turn to be printed.
  type :: result_t
    character(:), allocatable :: text      !< its one-line result, or its error; then its EXPECT misses
    integer :: split = 0                   !< length of the result (or error) part of text
    logical :: failed = .false.
  end type result_t
  character(len=:), allocatable :: decks(:)
  character(:), allocatable :: out_root
  logical :: quiet
  integer :: rank, ranks, verdict, failed, missed, count

  call MPI_Init()
  call MPI_Comm_rank(MPI_COMM_WORLD, rank)
  call MPI_Comm_size(MPI_COMM_WORLD, ranks)
  call ignore_file_size_signal()        ! past a file size limit a write fails and is reported
  call install_interrupt_cleanup()      ! an interrupt while a case folder is written leaves no partial folder
  call progress_configure(progress_off, 0.0_dp)   ! progress lines of many ranks would interleave on one stderr
  call read_command_line(verdict)
  call MPI_Bcast(verdict, 1, MPI_INTEGER, 0, MPI_COMM_WORLD)
  failed = 0
  missed = 0
  if (verdict == go) then
    count = size(decks)
    if (rank == 0) then
      if (ranks == 1) then
        call run_alone(failed, missed)
      else
        call dispatch(failed, missed)
      end if
      if (count > 1 .and. failed > 0) &
        write(0, '(a, i0, a, i0, a)') 'visco2d: ', failed, ' of ', count, ' decks failed'
      if (count > 1 .and. missed > 0) write(0, '(a, i0, a, i0, a)') 'visco2d: ', missed, ' of ', count, &
        ' decks missed their own EXPECT cards (their results are written)'
    else
      call work()
    end if
  end if
  flush(6)
  flush(0)
  call MPI_Finalize()
  if (rank == 0 .and. verdict == stop_usage) call c_exit(2_c_int)
  if (rank == 0 .and. failed > 0) call c_exit(1_c_int)
  if (rank == 0 .and. missed > 0) call c_exit(int(expect_missed_status, c_int))

contains

  !> Every rank reads the same command line; rank 0 alone reports a usage
  !> error (exit status 2), refuses decks that share a case name and prepares
  !> the output root (an empty or unwritable one is a usage error too).
  subroutine read_command_line(verdict)
    integer, intent(out) :: verdict
    character(:), allocatable :: argument, message
    type(error_t), allocatable :: problem
    integer :: i, count, longest, length
    out_root = 'out'
    quiet = .false.
    longest = 1
    do i = 1, command_argument_count()
      call get_command_argument(i, length=length)
      longest = max(longest, length)
    end do
    allocate(character(len=longest) :: decks(command_argument_count()))
    count = 0
    message = ''
    verdict = go
    i = 1
    do while (i <= command_argument_count() .and. len(message) == 0)
      call get_argument(i, argument)
      select case (argument)
      case ('-h', '--help')
        if (rank == 0) call print_help()
        verdict = stop_ok
        return
      case ('--version')
        if (rank == 0) print '(a)', 'visco2d-farm 0.1.0'
        verdict = stop_ok
        return
      case ('-o', '--out')
        if (i == command_argument_count()) then
          message = 'option '//argument//' needs a folder'
        else
          i = i + 1
          call get_argument(i, out_root)
        end if
      case ('-q', '--quiet')
        quiet = .true.
      case default
        if (argument(1:1) == '-') message = 'unknown option '//argument
        count = count + 1
        decks(count) = argument
      end select
      i = i + 1
    end do
    decks = decks(1:count)
    if (len(message) == 0 .and. count == 0) message = 'no deck given'
    if (len(message) == 0 .and. len_trim(out_root) == 0) &
      message = 'the output folder given with -o is empty: give a folder, e.g. -o out'
    if (len(message) == 0) message = duplicate_case_message(decks, out_root)
    if (len(message) > 0) then
      verdict = stop_usage
      if (rank == 0) then
        write(0, '(a)') 'visco2d-farm: '//message
        write(0, '(a)') 'usage: mpirun -np N visco2d-farm [-q] [-o DIR] DECK...   |   visco2d-farm --help'
      end if
      return
    end if
    if (rank /= 0) return
    call prepare_output_root(out_root, problem)
    if (allocated(problem)) then
      write(0, '(a)') 'visco2d: error: '//error_text(problem)
      verdict = stop_usage
    end if
  end subroutine read_command_line

  !> One rank: every deck in order, as the serial program runs them.
  subroutine run_alone(failed, missed)
    integer, intent(inout) :: failed, missed
    character(:), allocatable :: line, misses
    type(error_t), allocatable :: error
    integer :: k
    do k = 1, size(decks)
      call run_batch_deck(trim(decks(k)), out_root, line, error, misses)
      call report(allocated(error), line, misses, failed, missed)
    end do
  end subroutine run_alone

  !> Rank 0 of several: answer each rank's report (its previous deck's result)
  !> with the index of the next deck, or 0 when none is left; keep the results
  !> that come early and print them in deck order. The wait polls every 2 ms
  !> and sleeps in between, so this rank takes almost no processor time.
  subroutine dispatch(failed, missed)
    integer, intent(inout) :: failed, missed
    type(MPI_Request) :: request
    type(MPI_Status) :: status
    type(result_t), allocatable :: results(:)
    integer :: header(4), next, printed, stopped, source, none, ignored
    logical :: arrived
    allocate(results(size(decks)))
    next = 1
    none = 0
    printed = 0
    stopped = 0
    do while (stopped < ranks - 1)
      call MPI_Irecv(header, 4, MPI_INTEGER, MPI_ANY_SOURCE, tag_report, MPI_COMM_WORLD, request)
      arrived = .false.
      do
        call MPI_Test(request, arrived, status)
        if (arrived) exit
        ignored = c_usleep(2000_c_int)
      end do
      source = status%MPI_SOURCE
      if (header(1) > 0) then          ! header: deck index, 1 if it failed, length of its text, of its result part
        allocate(character(len=header(3)) :: results(header(1))%text)
        if (header(3) > 0) call MPI_Recv(results(header(1))%text, header(3), MPI_CHARACTER, source, tag_text, &
                                         MPI_COMM_WORLD, MPI_STATUS_IGNORE)
        results(header(1))%failed = header(2) == 1
        results(header(1))%split = header(4)
        do while (printed < size(decks))
          if (.not. allocated(results(printed + 1)%text)) exit
          printed = printed + 1
          associate (result => results(printed))
          call report(result%failed, result%text(:result%split), result%text(result%split + 1:), failed, missed)
          end associate
          deallocate(results(printed)%text)
        end do
      end if
      if (next <= size(decks)) then
        call MPI_Send(next, 1, MPI_INTEGER, source, tag_work, MPI_COMM_WORLD)
        next = next + 1
      else
        call MPI_Send(none, 1, MPI_INTEGER, source, tag_work, MPI_COMM_WORLD)
        stopped = stopped + 1
      end if
    end do
  end subroutine dispatch

  !> A rank other than 0: report (nothing at first), receive a deck index, run
  !> that deck, report its result; until rank 0 answers 0.
  subroutine work()
    character(:), allocatable :: line, misses, text
    type(error_t), allocatable :: error
    integer :: header(4), index
    header = [0, 0, 0, 0]
    do
      call MPI_Send(header, 4, MPI_INTEGER, 0, tag_report, MPI_COMM_WORLD)
      if (header(3) > 0) call MPI_Send(text, header(3), MPI_CHARACTER, 0, tag_text, MPI_COMM_WORLD)
      call MPI_Recv(index, 1, MPI_INTEGER, 0, tag_work, MPI_COMM_WORLD, MPI_STATUS_IGNORE)
      if (index == 0) exit
      call run_batch_deck(trim(decks(index)), out_root, line, error, misses)
      text = line//misses
      header = [index, merge(1, 0, allocated(error)), len(text), len(line)]
    end do
  end subroutine work

  !> Print a deck's result as the serial program does: its line on stdout
  !> (unless quiet), or its error on stderr; then the EXPECT cards it
  !> missed on stderr (miss_report), counted in `missed`.
  subroutine report(deck_failed, text, misses, failed, missed)
    logical, intent(in) :: deck_failed
    character(*), intent(in) :: text, misses
    integer, intent(inout) :: failed, missed
    if (deck_failed) then
      failed = failed + 1
      write(0, '(a)') 'visco2d: error: '//text
      flush(0)
    else if (.not. quiet) then
      print '(a)', text
      flush(6)
    end if
    if (.not. deck_failed .and. len(misses) > 0) then
      missed = missed + 1
      write(0, '(a)') misses
      flush(0)
    end if
  end subroutine report

  subroutine print_help()
    print '(a)', 'visco2d-farm - the decks of a batch over MPI ranks (a task farm)'
    print '(a)', ''
    print '(a)', 'usage:'
    print '(a)', '  mpirun -np N visco2d-farm [-q] [-o DIR] DECK...'
    print '(a)', ''
    print '(a)', 'Runs the decks as `visco2d [-q] [-o DIR] DECK...` would, one deck at a time per'
    print '(a)', 'rank: the same DIR/<case>/ folders, the same one-line result per deck, printed'
    print '(a)', 'in deck order, the same errors. Rank 0 hands out the decks (with N > 1 it runs'
    print '(a)', 'none itself: use one rank more than cores). Exit status 1 if any deck failed,'
    print '(a)', '2 for usage errors (and two decks with the same case name), 3 if every deck ran'
    print '(a)', 'but one missed its own EXPECT cards. See doc/command_line.md.'
    print '(a)', ''
    print '(a)', 'options:'
    print '(a)', '  -o, --out DIR   output root folder (default: out)'
    print '(a)', '  -q, --quiet     do not print the one-line result of each deck'
    print '(a)', '  -h, --help      this text'
    print '(a)', '      --version   program version'
  end subroutine print_help
#else
  write(0, '(a)') 'visco2d-farm: built without MPI: make mpi'
  flush(0)
  call c_exit(2_c_int)
#endif
end program visco2d_farm
