exec ls
