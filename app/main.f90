program feps_main
  implicit none
end program feps_main
