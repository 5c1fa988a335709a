!> visco2d command line:
!>   visco2d [options] DECK...     run decks into OUT/<deck stem>/
!>   visco2d check DECK...         parse and check, print mesh statistics and effects
program visco2d
  use visco2d_error, only: error_t, error_text
  use visco2d_record, only: record_t
  use visco2d_driver, only: run_deck, check_deck, run_line
  use, intrinsic :: iso_c_binding, only: c_int
  implicit none
  interface
    subroutine c_exit(status) bind(c, name='exit')
      import :: c_int
      integer(c_int), value :: status
    end subroutine c_exit
  end interface
  character(:), allocatable :: out_root, argument
  character(len=:), allocatable :: decks(:)
  integer :: i, count, failed, length
  logical :: quiet, checking
  type(error_t), allocatable :: error
  type(record_t) :: record

  out_root = 'out'
  quiet = .false.
  checking = .false.
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
  if (count == 0) call usage_error('no deck given')

  failed = 0
  do i = 1, count
    length = len_trim(decks(i))
    if (checking) then
      call check_deck(decks(i)(1:length), error)
    else
      call run_deck(decks(i)(1:length), out_root, record, error)
      if (.not. allocated(error) .and. .not. quiet) print '(a)', run_line(record)
    end if
    if (allocated(error)) then
      failed = failed + 1
      write(0, '(a)') 'visco2d: error: '//error_text(error)
      deallocate(error)
    end if
  end do
  if (count > 1 .and. failed > 0) write(0, '(a, i0, a, i0, a)') 'visco2d: ', failed, ' of ', count, ' decks failed'
  flush(6)
  flush(0)
  if (failed > 0) call c_exit(1_c_int)

contains

  subroutine get_argument(position, value)
    integer, intent(in) :: position
    character(:), allocatable, intent(out) :: value
    integer :: n
    call get_command_argument(position, length=n)
    allocate(character(len=n) :: value)
    call get_command_argument(position, value)
  end subroutine get_argument

  subroutine usage_error(message)
    character(*), intent(in) :: message
    write(0, '(a)') 'visco2d: '//message
    write(0, '(a)') 'usage: visco2d [-o DIR] [-q] DECK...   |   visco2d check DECK...   |   visco2d --help'
    flush(0)
    call c_exit(2_c_int)
  end subroutine usage_error

  subroutine print_help()
    print '(a)', 'visco2d - axisymmetric / plane-strain viscoelastic finite elements (fruit impact)'
    print '(a)', ''
    print '(a)', 'usage:'
    print '(a)', '  visco2d [options] DECK...   run each card deck; results go to OUT/<deck name>/'
    print '(a)', '  visco2d check DECK...       read and check decks without solving; print the mesh'
    print '(a)', '                              statistics (nodes, elements, half-bandwidth) and the'
    print '(a)', '                              active effects'
    print '(a)', ''
    print '(a)', 'options:'
    print '(a)', '  -o, --out DIR   output root folder (default: out)'
    print '(a)', '  -q, --quiet     do not print the one-line result of each deck'
    print '(a)', '  -h, --help      this text'
    print '(a)', '      --version   program version'
    print '(a)', ''
    print '(a)', 'Each case folder holds listing.txt, summary.txt (key = value), history.csv and'
    print '(a)', 'results.h5. A deck that fails leaves no case folder behind; the run goes on with'
    print '(a)', 'the next deck, and the exit status is 1 if any deck failed (2 for usage errors).'
    print '(a)', 'Errors read  file:line:column: CARD: message.  The card format is in README.md.'
  end subroutine print_help
end program visco2d
