!> The batch of decks of the two programs that run one, visco2d (serially)
!> and visco2d-farm (over MPI ranks): the rule, checked by both, that no two
!> decks of a batch have the same case name, and the run of one deck that
!> returns the line or the error text to print for it (the farm's ranks send
!> it to rank 0, which prints in deck order).
module visco2d_batch
  use visco2d_error, only: error_t, error_text
  use visco2d_record, only: record_t
  use visco2d_driver, only: run_deck, case_name_of
  use visco2d_expect, only: run_line, expect_tally_t, miss_report
  use visco2d_sorting, only: sorted_order
  implicit none
  private

  public :: duplicate_case_message, run_batch_deck

contains

  !> Empty if every deck of the batch has its own case name (the deck's file
  !> name without its extension: the folder OUT/<case>/ it writes); otherwise
  !> why the batch is refused, naming two decks that share a name: the second
  !> would silently replace the first one's folder. The names are sorted
  !> (stable merge sort), so a batch of many thousands of decks is checked at once.
  function duplicate_case_message(decks, out_root) result(message)
    character(*), intent(in) :: decks(:)     !< the deck paths (blank-padded)
    character(*), intent(in) :: out_root     !< the output root (for the message)
    character(:), allocatable :: message
    character(len=:), allocatable :: names(:)
    integer, allocatable :: order(:)
    integer :: i, k, longest, first, second
    longest = 1
    do i = 1, size(decks)
      longest = max(longest, len(case_name_of(trim(decks(i)))))
    end do
    allocate(character(len=longest) :: names(size(decks)))
    do i = 1, size(decks)
      names(i) = case_name_of(trim(decks(i)))
    end do
    order = sorted_order(names)
    message = ''
    do k = 2, size(order)
      first = order(k - 1)
      second = order(k)
      if (names(first) /= names(second)) cycle
      if (decks(first) == decks(second)) then
        message = 'the deck '//trim(decks(second))//' is given twice: its second run would replace the folder '// &
          out_root//'/'//trim(names(second))//'/ of the first; give it once'
      else
        message = 'the decks '//trim(decks(first))//' and '//trim(decks(second))//' have the same case name "'// &
          trim(names(second))//'": both would write the folder '//out_root//'/'//trim(names(second))// &
          '/; rename one of them or run them with separate -o folders'
      end if
      return
    end do
  end function duplicate_case_message


  !> Run one deck of a batch into out_root/<case>/ (run_deck): on success, line
  !> is its one-line result (run_line) and `misses` the lines to print on
  !> stderr for its EXPECT cards outside their RTOL ('' if none: miss_report);
  !> on failure, error is set and line is the error's text as the programs
  !> print it after "visco2d: error: ".
  subroutine run_batch_deck(path, out_root, line, error, misses)
    character(*), intent(in) :: path, out_root
    character(:), allocatable, intent(out) :: line
    type(error_t), allocatable, intent(out) :: error
    character(:), allocatable, intent(out), optional :: misses
    type(record_t) :: record
    type(expect_tally_t) :: tally
    call run_deck(path, out_root, record, error, tally)
    if (present(misses)) misses = ''
    if (allocated(error)) then
      line = error_text(error)
    else
      line = run_line(record, tally)
      if (present(misses)) misses = miss_report(tally)
    end if
  end subroutine run_batch_deck
end module visco2d_batch
