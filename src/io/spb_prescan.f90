!> A lexical pass over a namelist deck before Fortran reads it.
!>
!> gfortran's namelist reader skips unknown groups silently and reports an unterminated
!> string as a missing group; this pass finds the groups and the variable names the user
!> wrote, so that such decks get a precise error and the echo can mark values as input.
module spb_prescan
   use spb_error, only: spb_error_t, make_error
   use spb_strings, only: itoa, lower
   use spb_kinds, only: path_len
   use spb_sys, only: sys_file_kind, file_regular, file_other
   implicit none
   private
   public :: deck_scan_t, scan_deck, has_group, has_var, assignment_text, group_preamble

   integer, parameter :: key_len = 64
   !> the UTF-8 byte-order mark, read as nothing at the start of a deck or table
   character(len=3), parameter :: utf8_bom = achar(239) // achar(187) // achar(191)

   !> Where the scan of the deck text is.
   type :: lexer_t
      integer :: n = 0                       !! length of the text
      integer :: i = 1                       !! next character
      integer :: line = 1                    !! its line
      integer :: group_line = 0              !! line of the open group
      logical :: in_group = .false.          !! inside a group
      character(len=:), allocatable :: group !! the open (or last) group's name
      character(len=:), allocatable :: var   !! the last variable assigned
      character(len=key_len), allocatable :: whole(:)   !! 'group:variable' set whole
   end type lexer_t

   type :: deck_scan_t
      character(len=key_len), allocatable :: groups(:)   !! group names in order of appearance
      character(len=key_len), allocatable :: keys(:)     !! 'group:variable' for every assignment
      integer, allocatable :: first(:), last(:)          !! each assignment's text in `text`
      integer, allocatable :: group_first(:)             !! each group's text after its name
      integer, allocatable :: group_last(:)              !! ... up to its '/' (excluded)
      character(len=:), allocatable :: text              !! the deck
   end type deck_scan_t

contains

   !> Read the file at path and scan it.
   subroutine scan_deck(path, known_groups, scan, err)
      character(len=*), intent(in) :: path               !! deck file
      character(len=*), intent(in) :: known_groups(:)    !! accepted group names
      type(deck_scan_t), intent(out) :: scan             !! groups and variables found
      type(spb_error_t), allocatable, intent(out) :: err   !! the error (allocated: it failed)
      character(len=:), allocatable :: text
      integer :: u, ios, fsize
      character(len=256) :: msg

      if (sys_file_kind(path) == file_other) then
         ! a FIFO would block the open (or be read once, by the scan only), a device endlessly
         call make_error(err, 'deck: ''' // trim(path) // ''' is not a regular file (a FIFO, ' &
                         // 'a device or a socket); give the deck as a file')
         return
      end if
      open(newunit=u, file=path, status='old', action='read', access='stream', &
           form='unformatted', iostat=ios, iomsg=msg)
      if (ios /= 0) then
         call make_error(err, 'deck: cannot open ''' // trim(path) // ''': ' // trim(msg))
         return
      end if
      inquire(unit=u, size=fsize)
      if (fsize > 10 * 1024 * 1024) then
         close(u)
         call make_error(err, 'deck: ''' // trim(path) // ''' is larger than 10 MiB')
         return
      end if
      allocate(character(len=max(fsize, 0)) :: text)
      if (fsize > 0) read(u, iostat=ios, iomsg=msg) text
      close(u)
      if (ios /= 0) then
         call make_error(err, 'deck: cannot read ''' // trim(path) // ''': ' // trim(msg))
         return
      end if
      call scan_text(text, known_groups, scan, err)
   end subroutine scan_deck

   !> Scan deck text: groups (each known, at most once, terminated) and assignments.
   subroutine scan_text(text, known_groups, scan, err)
      character(len=*), intent(in) :: text               !! whole deck
      character(len=*), intent(in) :: known_groups(:)    !! accepted group names
      type(deck_scan_t), intent(out) :: scan   !! the prescan of the deck
      type(spb_error_t), allocatable, intent(out) :: err   !! the error (allocated: it failed)
      type(lexer_t) :: lx
      character :: c

      allocate(scan%groups(0), scan%keys(0), lx%whole(0), scan%first(0), scan%last(0), &
               scan%group_first(0), scan%group_last(0))
      scan%text = text
      lx%n = len(text)
      lx%group = ''
      lx%var = ''
      ! a UTF-8 byte-order mark (editors on Windows write one) is no text of the deck
      if (lx%n >= 3) then
         if (text(1:3) == utf8_bom) lx%i = 4
      end if
      do while (lx%i <= lx%n)
         c = text(lx%i:lx%i)
         if (c == achar(10)) then
            lx%line = lx%line + 1
            lx%i = lx%i + 1
         else if (c == '!') then
            call skip_comment(lx, text, err)
         else if (c == '''' .or. c == '"') then
            call skip_string(lx, text, err)
         else if (c == '&' .or. c == '$') then
            call group_marker(lx, text, known_groups, scan, err)
         else if (c == '/') then
            if (.not. lx%in_group) then
               call make_error(err, 'deck: line ' // itoa(lx%line) // ': ''/'' outside any group')
               return
            end if
            lx%in_group = .false.
            call close_assignment(scan, lx%i - 1)
            scan%group_last = [scan%group_last, lx%i - 1]
            lx%i = lx%i + 1
         else if (is_letter(c)) then
            call name_or_assignment(lx, text, scan, err)
         else if (c == achar(13) .or. c == achar(9) .or. c == ' ') then
            lx%i = lx%i + 1
         else
            if (.not. lx%in_group) then
               call make_error(err, 'deck: line ' // itoa(lx%line) // ': text outside any &group')
               return
            end if
            if (iachar(c) < 32 .or. iachar(c) > 126) then
               call make_error(err, '&' // lx%group // ': line ' // itoa(lx%line) &
                               // ': character code ' // itoa(iachar(c)) // ' is not deck text')
               return
            end if
            lx%i = lx%i + 1
         end if
         if (allocated(err)) return
      end do
      if (lx%in_group) then
         call make_error(err, '&' // lx%group // ': group opened at line ' // itoa(lx%group_line) &
                         // ' is not terminated by ''/''')
      end if
   end subroutine scan_text

   !> A comment from '!' to the end of the line: no control characters in it.
   subroutine skip_comment(lx, text, err)
      type(lexer_t), intent(inout) :: lx   !! where the scan is
      character(len=*), intent(in) :: text   !! the deck text
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      do while (lx%i <= lx%n)
         if (text(lx%i:lx%i) == achar(10)) exit
         if (is_control(text(lx%i:lx%i))) then
            if (lx%in_group) then
               call make_error(err, '&' // lx%group // ': line ' // itoa(lx%line) // &
                  ': character code ' // itoa(iachar(text(lx%i:lx%i))) // &
                  ' in a comment is not deck text')
            else
               call make_error(err, 'deck: line ' // itoa(lx%line) // ': character code ' // &
                  itoa(iachar(text(lx%i:lx%i))) // ' in a comment is not deck text')
            end if
            return
         end if
         lx%i = lx%i + 1
      end do
   end subroutine skip_comment

   !> A quoted string (a doubled quote stands for one), inside a group, closed on the line
   !> it opens on (a string running over a line end is a missing quote: the quote that
   !> seems to close it belongs to a later value), not longer than a string variable,
   !> without control characters (a tab included). Messages name the variable assigned.
   subroutine skip_string(lx, text, err)
      type(lexer_t), intent(inout) :: lx   !! where the scan is
      character(len=*), intent(in) :: text   !! the deck text
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      character :: quote, c
      integer :: j
      if (.not. lx%in_group) then
         call make_error(err, 'deck: line ' // itoa(lx%line) // ': text outside any &group')
         return
      end if
      quote = text(lx%i:lx%i)
      lx%i = lx%i + 1
      j = lx%i
      do
         if (lx%i - j > path_len - 1) then
            ! longer than any string variable: gfortran would cut it with a warning
            call make_error(err, string_where(lx) // 'a string longer than ' &
                            // itoa(path_len - 1) // ' characters (line ' // &
                            itoa(lx%line) // ')')
            return
         end if
         if (lx%i > lx%n) then
            call make_error(err, string_where(lx) // 'unterminated string starting at line ' &
                            // itoa(lx%line))
            return
         end if
         c = text(lx%i:lx%i)
         if (c == quote) then
            if (lx%i < lx%n) then
               if (text(lx%i+1:lx%i+1) == quote) then
                  lx%i = lx%i + 2
                  cycle
               end if
            end if
            lx%i = lx%i + 1
            exit
         end if
         if (c == achar(10) .or. c == achar(13)) then
            call make_error(err, string_where(lx) // 'unterminated string starting at line ' &
                            // itoa(lx%line) // ' (a string closes on its own line)')
            return
         end if
         if (is_control(c) .or. c == achar(9)) then
            call make_error(err, string_where(lx) // 'character code ' // itoa(iachar(c)) // &
                            ' in a string (line ' // itoa(lx%line) // ') is not deck text')
            return
         end if
         lx%i = lx%i + 1
      end do
   end subroutine skip_string

   !> '&name' (or '$name') opens a known group not given before; '&end' closes one.
   subroutine group_marker(lx, text, known_groups, scan, err)
      type(lexer_t), intent(inout) :: lx   !! where the scan is
      character(len=*), intent(in) :: text   !! the deck text
      character(len=*), intent(in) :: known_groups(:)   !! accepted group names
      type(deck_scan_t), intent(inout) :: scan   !! the prescan of the deck
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      character(len=:), allocatable :: word
      integer :: j
      j = lx%i + 1
      call read_word(text, j, word)
      if (len(word) == 0) then
         call make_error(err, 'deck: line ' // itoa(lx%line) // ': ''' // text(lx%i:lx%i) // &
                         ''' without a group name')
         return
      end if
      if (word == 'end') then
         if (.not. lx%in_group) then
            call make_error(err, 'deck: line ' // itoa(lx%line) // ': &end outside any group')
            return
         end if
         lx%in_group = .false.
         call close_assignment(scan, lx%i - 1)
         scan%group_last = [scan%group_last, lx%i - 1]
      else
         if (lx%in_group) then
            call make_error(err, '&' // lx%group // ': not terminated by ''/'' before &' // word &
                            // ' at line ' // itoa(lx%line))
            return
         end if
         if (.not. any(known_groups == word)) then
            call make_error(err, '&' // word // ': unknown group at line ' // itoa(lx%line) &
                            // ' (known: ' // join_groups(known_groups) // ')')
            return
         end if
         if (any(scan%groups == word)) then
            call make_error(err, '&' // word // ': group given twice (again at line ' &
                            // itoa(lx%line) // ')')
            return
         end if
         scan%groups = [character(len=key_len) :: scan%groups, word]
         scan%group_first = [scan%group_first, j]
         lx%group = word
         lx%var = ''
         lx%group_line = lx%line
         lx%in_group = .true.
      end if
      lx%i = j
   end subroutine group_marker

   !> A name inside a group; followed by an optional subscript and '=' it starts an
   !> assignment (a whole variable may be set once; elements, var(2) = ..., apart).
   subroutine name_or_assignment(lx, text, scan, err)
      type(lexer_t), intent(inout) :: lx   !! where the scan is
      character(len=*), intent(in) :: text   !! the deck text
      type(deck_scan_t), intent(inout) :: scan   !! the prescan of the deck
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      character(len=:), allocatable :: word
      integer :: j, name_start, depth
      logical :: subscripted
      name_start = lx%i
      j = lx%i
      call read_word(text, j, word)
      if (.not. lx%in_group) then
         call make_error(err, 'deck: line ' // itoa(lx%line) // ': text outside any &group ('''&
                         // word // '''); comments start with !')
         return
      end if
      lx%i = j
      call skip_blanks(lx, text)
      subscripted = .false.
      if (lx%i <= lx%n) then
         if (text(lx%i:lx%i) == '(') then
            subscripted = .true.
            depth = 0
            do while (lx%i <= lx%n)
               if (text(lx%i:lx%i) == '(') depth = depth + 1
               if (text(lx%i:lx%i) == ')') depth = depth - 1
               if (text(lx%i:lx%i) == achar(10)) lx%line = lx%line + 1
               lx%i = lx%i + 1
               if (depth == 0) exit
            end do
            call skip_blanks(lx, text)
         end if
      end if
      if (lx%i > lx%n) return
      if (text(lx%i:lx%i) /= '=') return
      ! a whole variable set twice is a typo somewhere (the namelist read would silently keep
      ! the last value)
      lx%var = word
      if (.not. subscripted) then
         if (any(lx%whole == lx%group // ':' // word)) then
            call make_error(err, '&' // lx%group // ': ' // word // ': given twice ' // &
                            '(again at line ' // itoa(lx%line) // ')')
            return
         end if
         lx%whole = [character(len=key_len) :: lx%whole, lx%group // ':' // word]
      end if
      scan%keys = [character(len=key_len) :: scan%keys, lx%group // ':' // word]
      call close_assignment(scan, name_start - 1)
      scan%first = [scan%first, name_start]
      scan%last = [scan%last, 0]
      lx%i = lx%i + 1
   end subroutine name_or_assignment

   !> Past blanks and tabs (not line ends).
   pure subroutine skip_blanks(lx, text)
      type(lexer_t), intent(inout) :: lx   !! where the scan is
      character(len=*), intent(in) :: text   !! the deck text
      do while (lx%i <= lx%n)
         if (text(lx%i:lx%i) /= ' ' .and. text(lx%i:lx%i) /= achar(9)) exit
         lx%i = lx%i + 1
      end do
   end subroutine skip_blanks

   !> End the open assignment (if any) at text position last.
   pure subroutine close_assignment(scan, last)
      type(deck_scan_t), intent(inout) :: scan   !! the prescan of the deck
      integer, intent(in) :: last   !! text position where it ends
      integer :: k
      k = size(scan%last)
      if (k == 0) return
      if (scan%last(k) == 0) scan%last(k) = last
   end subroutine close_assignment

   !> Assignment k as a one-assignment namelist record '&group var = value /' (empty when
   !> it belongs to another group): reading these one by one finds the one that fails.
   function assignment_text(scan, group, k, var) result(record)
      type(deck_scan_t), intent(in) :: scan   !! the prescan of the deck
      character(len=*), intent(in) :: group   !! group name
      integer, intent(in) :: k                          !! 1 .. size(scan%keys)
      character(len=:), allocatable, intent(out) :: var !! its variable name
      character(len=:), allocatable :: record
      integer :: c
      record = ''
      c = index(scan%keys(k), ':')
      var = trim(scan%keys(k)(c + 1:))
      if (scan%keys(k)(:c - 1) /= group) return
      record = '&' // group // ' ' // scan%text(scan%first(k):max(scan%first(k), scan%last(k))) &
               // ' /'
   end function assignment_text

   !> The text of a group before its first assignment ('' when none): what a namelist read
   !> of the group would meet before any variable.
   function group_preamble(scan, group) result(text)
      type(deck_scan_t), intent(in) :: scan   !! the prescan of the deck
      character(len=*), intent(in) :: group   !! group name
      character(len=:), allocatable :: text
      integer :: g, k, last
      text = ''
      if (.not. allocated(scan%groups)) return
      g = findloc(scan%groups, group, 1)
      if (g == 0 .or. g > size(scan%group_last)) return
      last = scan%group_last(g)
      do k = 1, size(scan%keys)
         if (scan%first(k) > scan%group_first(g) .and. scan%first(k) <= last) then
            last = scan%first(k) - 1
            exit
         end if
      end do
      text = scan%text(scan%group_first(g):last)
   end function group_preamble

   !> True when the group appears in the deck.
   logical function has_group(scan, group)
      type(deck_scan_t), intent(in) :: scan   !! the prescan of the deck
      character(len=*), intent(in) :: group   !! group name
      has_group = .false.
      if (allocated(scan%groups)) has_group = any(scan%groups == group)
   end function has_group

   !> True when the deck assigns the variable (any element of it) in the group.
   logical function has_var(scan, group, var)
      type(deck_scan_t), intent(in) :: scan   !! the prescan of the deck
      character(len=*), intent(in) :: group   !! group name
      character(len=*), intent(in) :: var   !! variable name
      has_var = .false.     ! a deck built in memory has no scan
      if (allocated(scan%keys)) has_var = any(scan%keys == group // ':' // var)
   end function has_var

   !> '&group: variable: ' of the string being scanned ('&group: ' before any assignment).
   function string_where(lx) result(text)
      type(lexer_t), intent(in) :: lx   !! where the scan is
      character(len=:), allocatable :: text
      text = '&' // lx%group // ': '
      if (len(lx%var) > 0) text = text // lx%var // ': '
   end function string_where

   !> A control character other than tab, line feed and carriage return (binary junk).
   pure logical function is_control(c)
      character, intent(in) :: c   !! the character
      is_control = (iachar(c) < 32 .and. c /= achar(9) .and. c /= achar(10) .and. &
                    c /= achar(13)) .or. iachar(c) == 127
   end function is_control

   !> Whether c starts a name.
   pure logical function is_letter(c)
      character, intent(in) :: c   !! the character
      is_letter = (c >= 'a' .and. c <= 'z') .or. (c >= 'A' .and. c <= 'Z')
   end function is_letter

   !> Read an identifier starting at text(j:), lower-cased; j ends after it.
   subroutine read_word(text, j, word)
      character(len=*), intent(in) :: text   !! the deck text
      integer, intent(inout) :: j   !! where the word starts; on return, just after it
      character(len=:), allocatable, intent(out) :: word   !! the word, lower case
      integer :: j0
      character :: c
      j0 = j
      do while (j <= len(text))
         c = text(j:j)
         if (.not. (is_letter(c) .or. (c >= '0' .and. c <= '9') .or. c == '_' .or. c == '%')) exit
         j = j + 1
      end do
      word = lower(text(j0:j-1))
   end subroutine read_word

   !> The group names, comma-separated.
   pure function join_groups(names) result(s)
      character(len=*), intent(in) :: names(:)   !! the group names
      character(len=:), allocatable :: s
      integer :: k
      s = ''
      do k = 1, size(names)
         if (k > 1) s = s // ', '
         s = s // '&' // trim(names(k))
      end do
   end function join_groups
end module spb_prescan
