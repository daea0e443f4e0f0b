class Boom(BaseException):
    pass


raise Boom('kaboom')
